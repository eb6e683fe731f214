#pragma once
// Post-processing: nodal heat flux q = -k(T) grad T recovered by area-weighted averaging of the
// element values at the nodes, and error norms against a known field.
#include "tfmb-heat/problem.hpp"

#include <functional>

namespace tfmb::heat {

/// (N, 2) heat flux [W/m^2] per node.
Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor> nodal_heat_flux(
    const ThermalProblem& problem, const Eigen::VectorXd& node_temperature);

/// L2 norm over the mesh of T_h - T_exact [K m], with the accurate quadrature rule.
double l2_error(const SolidMesh& mesh, const Eigen::VectorXd& node_temperature,
                const std::function<double(double, double)>& exact);

/// Area [m^2] of the mesh.
double mesh_area(const SolidMesh& mesh);

}  // namespace tfmb::heat
