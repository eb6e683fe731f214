#include "tfmb-heat/boundary_terms.hpp"

#include "tfmb-heat/quadrature.hpp"
#include "tfmb-heat/shape_functions.hpp"

#include <cmath>
#include <stdexcept>

namespace tfmb::heat {

const char* condition_name(const BoundaryCondition& condition) {
  struct Visitor {
    const char* operator()(const ImposedTemperature&) const { return "imposed temperature"; }
    const char* operator()(const Convection&) const { return "convection"; }
    const char* operator()(const Radiation&) const { return "radiation"; }
    const char* operator()(const ImposedHeatFlux&) const { return "imposed heat flux"; }
    const char* operator()(const Adiabatic&) const { return "adiabatic"; }
  };
  return std::visit(Visitor{}, condition);
}

namespace {
void require_trace(const Trace& trace, const char* what) {
  if (trace.empty()) {
    throw std::invalid_argument(std::string("needs a ") + what +
                                " trace along the wall but none was given");
  }
}
}  // namespace

std::vector<BoundaryPoint> boundary_points(const SolidMesh& mesh, const BoundaryCurve& curve,
                                           const std::vector<double>& arc_length,
                                           const BoundaryCondition& condition,
                                           int boundary_index, double trace_tolerance) {
  if (std::holds_alternative<Adiabatic>(condition) ||
      std::holds_alternative<ImposedTemperature>(condition)) {
    return {};
  }
  if (const auto* c = std::get_if<Convection>(&condition)) {
    require_trace(c->heat_transfer_coefficient, "heat transfer coefficient");
    require_trace(c->adiabatic_wall_temperature, "adiabatic wall temperature");
    if (c->heat_transfer_coefficient.min_value() < 0.0) {
      throw std::invalid_argument("heat transfer coefficient is negative (min " +
                                  std::to_string(c->heat_transfer_coefficient.min_value()) +
                                  " W/(m^2 K))");
    }
  }
  if (const auto* r = std::get_if<Radiation>(&condition)) {
    if (!(r->emissivity >= 0.0 && r->emissivity <= 1.0)) {
      throw std::invalid_argument("emissivity " + std::to_string(r->emissivity) +
                                  " is outside [0, 1]");
    }
    if (!(r->environment_temperature >= 0.0)) {
      throw std::invalid_argument("environment temperature " +
                                  std::to_string(r->environment_temperature) +
                                  " K is negative");
    }
  }
  if (const auto* f = std::get_if<ImposedHeatFlux>(&condition)) require_trace(f->heat_flux, "heat flux");

  const int npe = curve.nodes_per_edge;
  const auto rule = gauss_legendre(npe == 2 ? 3 : 5);
  std::vector<BoundaryPoint> points;
  points.reserve(curve.size() * rule.points.size());
  double n[3], dn[3];
  for (std::size_t e = 0; e < curve.size(); ++e) {
    const auto edge = curve.edge(e);
    for (std::size_t q = 0; q < rule.points.size(); ++q) {
      edge_shape_functions(npe, rule.points[q], n, dn);
      BoundaryPoint p;
      p.count = npe;
      p.boundary = boundary_index;
      double dx = 0.0, dy = 0.0, s = 0.0;
      for (int a = 0; a < npe; ++a) {
        p.nodes[a] = edge[a];
        p.n[a] = n[a];
        dx += dn[a] * mesh.points(edge[a], 0);
        dy += dn[a] * mesh.points(edge[a], 1);
        s += n[a] * arc_length[e * npe + a];
      }
      p.weight = rule.weights[q] * std::hypot(dx, dy);
      if (const auto* c = std::get_if<Convection>(&condition)) {
        p.h = c->heat_transfer_coefficient.at(s, trace_tolerance);
        p.t_ref = c->adiabatic_wall_temperature.at(s, trace_tolerance);
      } else if (const auto* r = std::get_if<Radiation>(&condition)) {
        p.eps_sigma = r->emissivity * kStefanBoltzmann;
        p.t_env = r->environment_temperature;
      } else if (const auto* f = std::get_if<ImposedHeatFlux>(&condition)) {
        p.q_in = f->heat_flux.at(s, trace_tolerance);
      }
      points.push_back(p);
    }
  }
  return points;
}

std::vector<std::pair<std::int64_t, double>> imposed_temperatures(
    const BoundaryCurve& curve, const std::vector<double>& arc_length,
    const ImposedTemperature& condition, double trace_tolerance) {
  require_trace(condition.temperature, "wall temperature");
  std::vector<std::pair<std::int64_t, double>> values;
  values.reserve(curve.nodes.size());
  for (std::size_t i = 0; i < curve.nodes.size(); ++i) {
    values.emplace_back(curve.nodes[i], condition.temperature.at(arc_length[i], trace_tolerance));
  }
  return values;
}

}  // namespace tfmb::heat
