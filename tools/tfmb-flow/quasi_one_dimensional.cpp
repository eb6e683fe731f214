#include "quasi_one_dimensional.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace tfmb::flow {

double area_ratio_of_mach(double m, double g) {
  return 1.0 / m *
         std::pow(2.0 / (g + 1.0) * (1.0 + 0.5 * (g - 1.0) * m * m), 0.5 * (g + 1.0) / (g - 1.0));
}

double mach_of_area_ratio(double ratio, double g, bool supersonic) {
  if (ratio < 1.0)
    throw std::invalid_argument("area ratio below 1");
  double lo = supersonic ? 1.0 : 1e-12;
  double hi = supersonic ? 100.0 : 1.0;
  // area ratio decreases on the subsonic branch and increases on the supersonic one; halved
  // to the last bits (about 50 times; the start state inverts it once per node)
  for (int k = 0; k < 200 && hi - lo > 1e-15 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    const bool above = area_ratio_of_mach(mid, g) > ratio;
    if (above == supersonic)
      hi = mid;
    else
      lo = mid;
  }
  return 0.5 * (lo + hi);
}

double isentropic_pressure_ratio(double m, double g) {
  return std::pow(1.0 + 0.5 * (g - 1.0) * m * m, -g / (g - 1.0));
}

double normal_shock_mach(double m1, double g) {
  return std::sqrt((1.0 + 0.5 * (g - 1.0) * m1 * m1) / (g * m1 * m1 - 0.5 * (g - 1.0)));
}

double normal_shock_total_pressure_ratio(double m1, double g) {
  const double m2 = normal_shock_mach(m1, g);
  const double p2_p1 = 1.0 + 2.0 * g / (g + 1.0) * (m1 * m1 - 1.0);
  return p2_p1 * isentropic_pressure_ratio(m1, g) / isentropic_pressure_ratio(m2, g);
}

Quasi1dNozzle::Quasi1dNozzle(std::function<double(double)> area, double x_inlet, double x_throat,
                             double x_exit, double g, double pe)
    : area_(std::move(area)), x_throat_(x_throat), x_exit_(x_exit), gamma_(g) {
  (void)x_inlet;
  const double a_t = area_(x_throat);
  const double a_e = area_(x_exit);
  const double pe_subsonic_choked =
      isentropic_pressure_ratio(mach_of_area_ratio(a_e / a_t, g, false), g);
  if (pe >= 1.0)
    throw std::invalid_argument("exit pressure ratio must be below 1");
  if (pe >= pe_subsonic_choked) {
    const double me = std::sqrt(2.0 / (g - 1.0) * (std::pow(pe, -(g - 1.0) / g) - 1.0));
    a_star_1_ = a_star_2_ = a_e / area_ratio_of_mach(me, g);
    return;
  }
  choked_ = true;
  a_star_1_ = a_t;
  const double m_exit_sup = mach_of_area_ratio(a_e / a_t, g, true);
  const double pe_shock_at_exit = isentropic_pressure_ratio(m_exit_sup, g) *
                                  (1.0 + 2.0 * g / (g + 1.0) * (m_exit_sup * m_exit_sup - 1.0));
  if (pe <= pe_shock_at_exit) {
    exit_supersonic_ = true;
    a_star_2_ = a_t;
    return;
  }
  has_shock_ = true;
  auto exit_pressure = [&](double xs) {
    const double m1 = mach_of_area_ratio(area_(xs) / a_t, g, true);
    const double r = normal_shock_total_pressure_ratio(m1, g);
    const double me = mach_of_area_ratio(a_e / (a_t / r), g, false);
    return r * isentropic_pressure_ratio(me, g);
  };
  double lo = x_throat, hi = x_exit;  // exit pressure falls as the shock moves downstream
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    if (exit_pressure(mid) > pe)
      lo = mid;
    else
      hi = mid;
  }
  shock_x_ = 0.5 * (lo + hi);
  p0_ratio_ =
      normal_shock_total_pressure_ratio(mach_of_area_ratio(area_(shock_x_) / a_t, g, true), g);
  a_star_2_ = a_t / p0_ratio_;
}

double Quasi1dNozzle::mach(double x) const {
  // (a section below the sonic area, e.g. a duct narrowing again behind the shock, has no
  // quasi-1D solution: sonic there)
  auto branch = [&](double a_star, bool supersonic) {
    return mach_of_area_ratio(std::max(1.0, area_(x) / a_star), gamma_, supersonic);
  };
  if (!choked_ || x <= x_throat_)
    return branch(a_star_1_, false);
  if (has_shock_ && x > shock_x_)
    return branch(a_star_2_, false);
  return branch(a_star_1_, true);
}

double Quasi1dNozzle::total_pressure_ratio(double x) const {
  return (has_shock_ && x > shock_x_) ? p0_ratio_ : 1.0;
}

double Quasi1dNozzle::pressure_ratio(double x) const {
  return total_pressure_ratio(x) * isentropic_pressure_ratio(mach(x), gamma_);
}

double choked_mass_flux(double p0, double t0, double g, double r) {
  // rho* a* with the sonic state of the total conditions (Anderson 2003, eq. 5.21)
  return p0 / std::sqrt(r * t0) * std::sqrt(g) *
         std::pow(2.0 / (g + 1.0), 0.5 * (g + 1.0) / (g - 1.0));
}

double Quasi1dNozzle::mass_flow(double p0, double t0, double r) const {
  return choked_mass_flux(p0, t0, gamma_, r) * a_star_1_;
}

double DuctSections::area_at(double xq) const {
  if (xq <= x.front())
    return area.front();
  if (xq >= x.back())
    return area.back();
  const auto k = static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), xq) - x.begin());
  const double t = (xq - x[k - 1]) / (x[k] - x[k - 1]);
  return (1.0 - t) * area[k - 1] + t * area[k];
}

namespace {

// The span [y_lo, y_hi] of a convex cell on the line x = c, or false when the line misses it. An
// edge counts as crossed when its ends lie on either side of c, one side including c itself,
// so a line through a vertex or along an edge meets each cell of a column exactly once.
template <std::size_t N>
bool cell_span(const Mesh& mesh, const std::array<int, N>& cell, double c, double& y_lo,
               double& y_hi) {
  y_lo = std::numeric_limits<double>::infinity();
  y_hi = -y_lo;
  int crossings = 0;
  for (std::size_t k = 0; k < N; ++k) {
    const Vec2 a = mesh.points[static_cast<std::size_t>(cell[k])];
    const Vec2 b = mesh.points[static_cast<std::size_t>(cell[(k + 1) % N])];
    if ((a.x <= c) == (b.x <= c))
      continue;
    const double y = a.y + (c - a.x) / (b.x - a.x) * (b.y - a.y);
    y_lo = std::min(y_lo, y);
    y_hi = std::max(y_hi, y);
    ++crossings;
  }
  return crossings >= 2;
}

}  // namespace

DuctSections duct_sections(const Mesh& mesh, Geometry geometry, int stations) {
  if (stations < 2 || mesh.points.empty())
    throw std::invalid_argument("duct_sections: no stations");
  double x_min = std::numeric_limits<double>::infinity(), x_max = -x_min;
  for (const Vec2& p : mesh.points) {
    x_min = std::min(x_min, p.x);
    x_max = std::max(x_max, p.x);
  }
  DuctSections d;
  const double dx = (x_max - x_min) / stations;
  if (!(dx > 0.0))
    throw std::invalid_argument("duct_sections: the mesh has no extent in x");
  for (int k = 0; k < stations; ++k)
    d.x.push_back(x_min + (k + 0.5) * dx);
  d.area.assign(d.x.size(), 0.0);
  const double pi = std::acos(-1.0);
  auto add_cell = [&](const auto& cell) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int n : cell) {
      lo = std::min(lo, mesh.points[static_cast<std::size_t>(n)].x);
      hi = std::max(hi, mesh.points[static_cast<std::size_t>(n)].x);
    }
    const int k0 = std::max(0, static_cast<int>(std::ceil((lo - x_min) / dx - 0.5)));
    const int k1 = std::min(stations - 1, static_cast<int>(std::floor((hi - x_min) / dx - 0.5)));
    for (int k = k0; k <= k1; ++k) {
      double y_lo = 0.0, y_hi = 0.0;
      if (!cell_span(mesh, cell, d.x[static_cast<std::size_t>(k)], y_lo, y_hi))
        continue;
      d.area[static_cast<std::size_t>(k)] +=
          geometry == Geometry::axisymmetric
              ? pi * std::abs(y_hi * std::abs(y_hi) - y_lo * std::abs(y_lo))
              : y_hi - y_lo;
    }
  };
  for (const auto& t : mesh.triangles)
    add_cell(t);
  for (const auto& q : mesh.quads)
    add_cell(q);
  return d;
}

std::string Quasi1dStart::summary() const {
  char text[256];
  if (!choked) {
    std::snprintf(text, sizeof text,
                  "subsonic throughout (smallest section %.4g at x = %.4g m, exit %.4g)",
                  throat_area, throat_x, exit_area);
  } else if (has_shock) {
    std::snprintf(text, sizeof text,
                  "choked at x = %.4g m (A_exit/A_throat %.4g), normal shock at x = %.4g m",
                  throat_x, exit_area / throat_area, shock_x);
  } else {
    std::snprintf(text, sizeof text,
                  "choked at x = %.4g m (A_exit/A_throat %.4g), supersonic to the exit", throat_x,
                  exit_area / throat_area);
  }
  return text;
}

Quasi1dStart quasi_one_dimensional_start(const Mesh& mesh, Geometry geometry, const PerfectGas& gas,
                                         double p0, double t0, double p_exit) {
  // Several stations per column of cells, so that the throat and the shock are placed to a
  // fraction of a cell (NPARC's 480 x 120 cells: 1,920 stations, four per column).
  const int stations = std::clamp(
      static_cast<int>(8.0 * std::sqrt(static_cast<double>(mesh.num_cells()))), 200, 4000);
  const DuctSections sections = duct_sections(mesh, geometry, stations);
  for (double a : sections.area)
    if (!(a > 0.0))
      throw std::invalid_argument("quasi-1D start: a duct section with no fluid");
  const auto throat =
      std::min_element(sections.area.begin(), sections.area.end()) - sections.area.begin();
  Quasi1dStart start;
  start.throat_x = sections.x[static_cast<std::size_t>(throat)];
  start.throat_area = sections.area[static_cast<std::size_t>(throat)];
  start.exit_area = sections.area.back();
  const double g = gas.gamma;
  const Quasi1dNozzle q([&](double x) { return sections.area_at(x); }, sections.x.front(),
                        start.throat_x, sections.x.back(), g, p_exit / p0);
  start.choked = q.choked();
  start.has_shock = q.has_shock();
  start.shock_x = q.shock_position();
  start.states.reserve(mesh.points.size());
  for (const Vec2& p : mesh.points) {
    const double m = q.mach(p.x);
    const double t = t0 / (1.0 + 0.5 * (g - 1.0) * m * m);
    const double pressure = p0 * q.total_pressure_ratio(p.x) * isentropic_pressure_ratio(m, g);
    start.states.push_back({pressure / (gas.R * t), m * std::sqrt(g * gas.R * t), 0.0, pressure});
  }
  return start;
}

}  // namespace tfmb::flow
