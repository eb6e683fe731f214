#include "tfmb-heat/calculix_export.hpp"

#include "tfmb-heat/boundary_geometry.hpp"
#include "tfmb-heat/boundary_terms.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace tfmb::heat {

void write_calculix_input(std::ostream& out, const ThermalProblem& problem,
                          double initial_temperature) {
  const auto& mesh = *problem.mesh;
  if (!problem.contacts.empty() || problem.volumetric_source) {
    throw std::invalid_argument("CalculiX export: contacts and volumetric sources are not exported");
  }
  // ccx reads numeric fields of at most 20 characters: 14 significant digits fit.
  out.precision(14);
  out << "*HEADING\ntfmb-heat side-by-side deck (planar, unit depth)\n";
  out << "*NODE, NSET=NALL\n";
  for (Eigen::Index i = 0; i < mesh.points.rows(); ++i) {
    out << i + 1 << ", " << mesh.points(i, 0) << ", " << mesh.points(i, 1) << ", 0\n";
  }
  // Element faces of the plane heat elements: face k joins local nodes k and k+1 (ccx manual,
  // face numbering of 2D elements).
  std::map<std::pair<std::int64_t, std::int64_t>, std::pair<std::size_t, int>> faces;
  std::size_t cell = 0;
  std::map<int, std::vector<std::size_t>> cells_of_material;
  for (const auto& block : mesh.blocks) {
    if (block.type != ElementType::tri3 && block.type != ElementType::quad4) {
      throw std::invalid_argument("CalculiX export: only linear triangles and quads are exported");
    }
    // ccx 2.20 has no DC2D* elements; plane elements carry the temperature dof 11 and a pure
    // *HEAT TRANSFER step solves only for it.
    out << "*ELEMENT, TYPE=" << (block.type == ElementType::tri3 ? "CPS3" : "CPS4")
        << ", ELSET=EALL\n";
    const auto npe = static_cast<int>(nodes_per_element(block.type));
    for (std::size_t e = 0; e < block.size(); ++e, ++cell) {
      const auto nodes = block.element(e);
      out << cell + 1;
      for (auto node : nodes) out << ", " << node + 1;
      out << "\n";
      for (int k = 0; k < npe; ++k) {
        auto a = nodes[static_cast<std::size_t>(k)], b = nodes[static_cast<std::size_t>((k + 1) % npe)];
        faces[{std::min(a, b), std::max(a, b)}] = {cell, k + 1};
      }
      cells_of_material[mesh.cell_material[cell]].push_back(cell);
    }
  }
  for (const auto& [m, cells] : cells_of_material) {
    const auto& material = problem.materials[static_cast<std::size_t>(m)];
    out << "*ELSET, ELSET=EM" << m << "\n";
    for (std::size_t i = 0; i < cells.size(); ++i) out << cells[i] + 1 << ((i % 10 == 9) ? ",\n" : ", ");
    out << "\n*MATERIAL, NAME=M" << m << "\n*CONDUCTIVITY\n";
    const auto& k = material.conductivity;
    for (std::size_t i = 0; i < k.values().size(); ++i) {
      out << k.values()[i] << ", " << (k.is_constant() ? initial_temperature : k.temperatures()[i]) << "\n";
    }
    out << "*SOLID SECTION, ELSET=EM" << m << ", MATERIAL=M" << m << "\n1.\n";
  }
  // ccx reads this card with a limited field width: write the constant with 10 digits.
  out << "*PHYSICAL CONSTANTS, ABSOLUTE ZERO=0., STEFAN BOLTZMANN=5.670374419E-8\n";
  out << "*INITIAL CONDITIONS, TYPE=TEMPERATURE\nNALL, " << initial_temperature << "\n";
  out << "*STEP, INC=1000\n*HEAT TRANSFER, STEADY STATE\n1., 1.\n";
  // ccx's default criteria accept a residual flux of 0.5 % of the average flux (manual sec.
  // "Thermomechanical iterations"); tighten them so the comparison measures discretisation,
  // not the stopping point.
  out << "*CONTROLS, PARAMETERS=FIELD\n1e-9, 1e-9, 0., 0., 0.02, 1e-5, 1e-3, 1e-8\n";

  auto face_of = [&](std::span<const std::int64_t> edge, const std::string& name) {
    const auto key = std::make_pair(std::min(edge[0], edge[1]), std::max(edge[0], edge[1]));
    const auto it = faces.find(key);
    if (it == faces.end()) throw std::invalid_argument("CalculiX export: boundary '" + name + "' edge is not an element face");
    return it->second;
  };
  for (const auto& spec : problem.boundary_conditions) {
    const auto& curve = mesh.boundaries.at(spec.boundary);
    const auto s = boundary_arc_length(mesh, curve);
    const double tol = problem.trace_tolerance;
    if (const auto* imposed = std::get_if<ImposedTemperature>(&spec.condition)) {
      out << "*BOUNDARY\n";
      for (const auto& [node, value] : imposed_temperatures(curve, s, *imposed, tol)) {
        out << node + 1 << ", 11, 11, " << value << "\n";
      }
      continue;
    }
    for (std::size_t e = 0; e < curve.size(); ++e) {
      const auto [element, face] = face_of(curve.edge(e), spec.boundary);
      const double s_mid = 0.5 * (s[2 * e] + s[2 * e + 1]);
      if (const auto* c = std::get_if<Convection>(&spec.condition)) {
        out << "*FILM\n" << element + 1 << ", F" << face << ", "
            << c->adiabatic_wall_temperature.at(s_mid, tol) << ", "
            << c->heat_transfer_coefficient.at(s_mid, tol) << "\n";
      } else if (const auto* r = std::get_if<Radiation>(&spec.condition)) {
        out << "*RADIATE\n" << element + 1 << ", R" << face << ", " << r->environment_temperature
            << ", " << r->emissivity << "\n";
      } else if (const auto* f = std::get_if<ImposedHeatFlux>(&spec.condition)) {
        out << "*DFLUX\n" << element + 1 << ", S" << face << ", " << f->heat_flux.at(s_mid, tol) << "\n";
      }
    }
  }
  out << "*NODE PRINT, NSET=NALL\nNT\n*END STEP\n";
}

Eigen::VectorXd read_calculix_temperatures(const std::string& dat_path, std::size_t node_count) {
  std::ifstream in(dat_path);
  if (!in) throw std::runtime_error("cannot open CalculiX output " + dat_path);
  Eigen::VectorXd t = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(node_count), std::nan(""));
  std::string line;
  bool in_block = false;
  while (std::getline(in, line)) {
    if (line.find("temperatures") != std::string::npos) {
      in_block = true;
      continue;
    }
    if (!in_block) continue;
    std::istringstream fields(line);
    long node = 0;
    double value = 0.0;
    if (fields >> node >> value) {
      if (node >= 1 && static_cast<std::size_t>(node) <= node_count) t[node - 1] = value;
    }
  }
  return t;
}

}  // namespace tfmb::heat
