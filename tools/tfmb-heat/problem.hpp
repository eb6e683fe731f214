#pragma once
// A planar (per unit depth) conduction problem: mesh, materials, boundary conditions, contacts.
#include "tfmb-heat/boundary_conditions.hpp"
#include "tfmb-heat/mesh.hpp"
#include "tfmb-heat/property_table.hpp"

#include <functional>
#include <vector>

namespace tfmb::heat {

struct ThermalProblem {
  const SolidMesh* mesh = nullptr;               // not owned; must outlive the problem
  std::vector<Material> materials;               // indexed by mesh->cell_material
  std::vector<BoundarySpec> boundary_conditions;
  std::vector<ContactSpec> contacts;
  /// Volumetric heat source q''' [W/m^3] at (x, y) [m]; empty: none.
  std::function<double(double, double)> volumetric_source;
  /// Arc-length tolerance [m] for traces that stop just short of the wall ends.
  double trace_tolerance = 1e-9;
};

/// Tangent used by Newton. consistent: full Jacobian including dk/dT grad T and d(rho cp)/dT
/// (quadratic convergence, non-symmetric, solved by SparseLU). picard: k(T) frozen at the
/// iterate (symmetric, solved by SimplicialLDLT; linear convergence).
enum class Tangent { consistent, picard };

struct NewtonSettings {
  /// Converged when the largest nodal temperature update of an iteration is below this [K].
  double temperature_tolerance = 1e-8;
  int max_iterations = 30;
  /// Updates larger than this [K] are scaled down (guards radiation-dominated first iterations).
  double max_update = 500.0;
  Tangent tangent = Tangent::consistent;
  /// Called after every Newton iteration with its number (1, 2, ...), the residual [W/m] and
  /// the largest temperature update [K] (progress lines); empty: not called.
  std::function<void(int iteration, double residual, double largest_update)> on_iteration;
};

struct NewtonReport {
  int iterations = 0;
  bool converged = false;
  std::vector<double> max_update;     // [K] per iteration
  std::vector<double> residual_norm;  // [W/m] infinity norm of the free-node residual
  double assembly_seconds = 0.0;      // wall time in residual and tangent assembly
  double solve_seconds = 0.0;         // wall time in sparse factorisation and solution
};

}  // namespace tfmb::heat
