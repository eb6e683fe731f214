#include "mapping.hpp"
#include "tfmb/common/assert.hpp"
#include "tfmb/common/quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tfmb::loads {

const char* method_name(Method method) {
  return method == Method::linear ? "linear" : "conservative";
}

Resultant nodal_resultant(const BeamLine& beam, const std::vector<Vec2>& force,
                          const std::vector<double>& moment) {
  Resultant r;
  for (std::size_t i = 0; i < beam.node_count(); ++i) {
    r.force += force[i];
    r.moment += cross(beam.nodes()[i], force[i]) + moment[i];
  }
  return r;
}

void consistent_nodal_loads(const BeamLine& beam, const std::vector<Vec2>& q,
                            const std::vector<double>& m, std::vector<Vec2>& nodal_force,
                            std::vector<double>& nodal_moment) {
  const std::size_t n = beam.node_count();
  nodal_force.assign(n, Vec2::Zero());
  nodal_moment.assign(n, 0.0);
  for (std::size_t j = 0; j + 1 < n; ++j) {
    const double h = beam.element_length(j);
    // int N_a N_b ds over a linear element: h/3 on the diagonal, h/6 off it.
    nodal_force[j] += h / 6.0 * (2.0 * q[j] + q[j + 1]);
    nodal_force[j + 1] += h / 6.0 * (q[j] + 2.0 * q[j + 1]);
    nodal_moment[j] += h / 6.0 * (2.0 * m[j] + m[j + 1]);
    nodal_moment[j + 1] += h / 6.0 * (m[j] + 2.0 * m[j + 1]);
  }
}

namespace {

// Solves the consistent 1D mass matrix system M x = b (tridiagonal, symmetric positive
// definite) by the Thomas algorithm; b and x hold k columns.
std::vector<Eigen::Vector3d> solve_mass(const BeamLine& beam,
                                        const std::vector<Eigen::Vector3d>& b) {
  const std::size_t n = beam.node_count();
  std::vector<double> diag(n, 0.0), upper(n, 0.0);
  for (std::size_t j = 0; j + 1 < n; ++j) {
    const double h = beam.element_length(j);
    diag[j] += h / 3.0;
    diag[j + 1] += h / 3.0;
    upper[j] = h / 6.0;
  }
  std::vector<double> c(n, 0.0);
  std::vector<Eigen::Vector3d> d(n);
  c[0] = upper[0] / diag[0];
  d[0] = b[0] / diag[0];
  for (std::size_t i = 1; i < n; ++i) {
    const double denominator = diag[i] - upper[i - 1] * c[i - 1];
    c[i] = upper[i] / denominator;
    d[i] = (b[i] - upper[i - 1] * d[i - 1]) / denominator;
  }
  std::vector<Eigen::Vector3d> x(n);
  x[n - 1] = d[n - 1];
  for (std::size_t i = n - 1; i-- > 0;)
    x[i] = d[i] - c[i] * x[i + 1];
  return x;
}

FlapLoads map_conservative(const BeamLine& beam, const std::vector<const WallTrace*>& traces,
                           double width) {
  const std::size_t n = beam.node_count();
  std::vector<Eigen::Vector3d> nodal(n, Eigen::Vector3d::Zero());  // Fx, Fy, Mz
  for (const WallTrace* trace : traces) {
    for (std::size_t k = 0; k < trace->segment_count(); ++k) {
      const Vec2 p0 = trace->points[k];
      const Vec2 p1 = trace->points[k + 1];
      const double h = (p1 - p0).norm();
      // Split the segment where it crosses node lines, so that each piece maps into one
      // element and the quadrature integrates polynomials (on straight elements).
      std::vector<double> cuts = {0.0, 1.0};
      for (std::size_t i = 0; i < n; ++i) {
        const double f0 = beam.node_line_distance(i, p0);
        const double f1 = beam.node_line_distance(i, p1);
        if ((f0 < 0.0 && f1 > 0.0) || (f0 > 0.0 && f1 < 0.0))
          cuts.push_back(f0 / (f0 - f1));
      }
      std::sort(cuts.begin(), cuts.end());
      for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
        const double ua = cuts[c];
        const double ub = cuts[c + 1];
        if (!(ub > ua))
          continue;
        static const auto gauss_2 = quadrature::gauss_legendre_unit(2);  // on [0, 1]
        for (const auto& [g, w] : gauss_2) {
          const double u = ua + g * (ub - ua);
          const double weight = w * (ub - ua) * h * width;
          const Vec2 x = trace->position(k, u);
          const Vec2 t = trace->traction(k, u);
          const BeamProjection b = beam.project(x);
          // project() picks one of the beam's elements, so both of its nodes exist
          TFMB_ASSERT(b.element + 1 < n,
                      "projection on element " << b.element << " of a beam of " << n << " nodes");
          const double offset_moment = cross(x - b.point, t);
          const Eigen::Vector3d load(t.x(), t.y(), offset_moment);
          nodal[b.element] += (1.0 - b.xi) * weight * load;
          nodal[b.element + 1] += b.xi * weight * load;
        }
      }
    }
  }
  FlapLoads out;
  out.arc_length = beam.arc_length();
  out.nodal_force.resize(n);
  out.nodal_moment.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    out.nodal_force[i] = nodal[i].head<2>();
    out.nodal_moment[i] = nodal[i].z();
  }
  const std::vector<Eigen::Vector3d> distributed = solve_mass(beam, nodal);
  out.distributed_force.resize(n);
  out.distributed_moment.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    out.distributed_force[i] = distributed[i].head<2>();
    out.distributed_moment[i] = distributed[i].z();
  }
  return out;
}

FlapLoads map_linear(const BeamLine& beam, const std::vector<const WallTrace*>& traces,
                     double width, const WallField* field) {
  const std::size_t n = beam.node_count();
  FlapLoads out;
  out.arc_length = beam.arc_length();
  out.distributed_force.assign(n, Vec2::Zero());
  out.distributed_moment.assign(n, 0.0);
  for (Side side : {Side::inner, Side::outer}) {
    std::vector<const WallTrace*> side_traces;
    for (const WallTrace* t : traces) {
      if (t->side == side)
        side_traces.push_back(t);
    }
    if (side_traces.empty())
      continue;
    std::vector<WallSample> samples(n);
    for (std::size_t i = 0; i < n; ++i) {
      samples[i] = sample_at_node(beam, i, side_traces);
      if (field && samples[i].found) {
        const auto [p, tau] = (*field)(side, samples[i].point);
        samples[i].traction = -p * samples[i].normal + tau * samples[i].tangent;
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (!samples[i].found)
        continue;
      // Ratio of wall to beam arc length around node i (chords between the wall points of
      // the neighbouring nodes): 1 for a wall parallel to a straight beam, R_wall / R_beam on
      // concentric arcs.
      const std::size_t lo = i > 0 && samples[i - 1].found ? i - 1 : i;
      const std::size_t hi = i + 1 < n && samples[i + 1].found ? i + 1 : i;
      double ratio = 1.0;
      if (hi > lo) {
        double wall = 0.0;
        for (std::size_t a = lo; a < hi; ++a)
          wall += (samples[a + 1].point - samples[a].point).norm();
        ratio = wall / (beam.arc_length()[hi] - beam.arc_length()[lo]);
      }
      const Vec2 q = width * ratio * samples[i].traction;
      out.distributed_force[i] += q;
      out.distributed_moment[i] += cross(samples[i].point - beam.nodes()[i], q);
    }
  }
  consistent_nodal_loads(beam, out.distributed_force, out.distributed_moment, out.nodal_force,
                         out.nodal_moment);
  return out;
}

}  // namespace

WallSample sample_at_node(const BeamLine& beam, std::size_t node,
                          const std::vector<const WallTrace*>& side_traces) {
  WallSample best;
  double best_distance = std::numeric_limits<double>::infinity();
  const Vec2 r = beam.nodes()[node];
  for (const WallTrace* trace : side_traces) {
    for (std::size_t k = 0; k < trace->segment_count(); ++k) {
      const double f0 = beam.node_line_distance(node, trace->points[k]);
      const double f1 = beam.node_line_distance(node, trace->points[k + 1]);
      if ((f0 > 0.0 && f1 > 0.0) || (f0 < 0.0 && f1 < 0.0) || f0 == f1)
        continue;
      const double u = f0 / (f0 - f1);
      const Vec2 x = trace->position(k, u);
      const double distance = (x - r).norm();
      if (distance < best_distance) {
        best_distance = distance;
        best.found = true;
        best.point = x;
        best.traction = trace->smooth_traction(k, u);
        best.normal = trace->smooth_normal(k, u);
        best.tangent = trace->normal_sign * Vec2(best.normal.y(), -best.normal.x());
      }
    }
  }
  if (!best.found) {
    // The node line misses the wall (a wall that stops short of the beam end, within the
    // coverage tolerance): take the nearest wall end point.
    for (const WallTrace* trace : side_traces) {
      for (std::size_t e : {std::size_t{0}, trace->points.size() - 1}) {
        const double distance = (trace->points[e] - r).norm();
        if (distance < best_distance) {
          best_distance = distance;
          best.found = true;
          best.point = trace->points[e];
          const std::size_t k = e == 0 ? 0 : trace->segment_count() - 1;
          best.traction = trace->smooth_traction(k, e == 0 ? 0.0 : 1.0);
          best.normal = trace->smooth_normal(k, e == 0 ? 0.0 : 1.0);
          best.tangent = trace->normal_sign * Vec2(best.normal.y(), -best.normal.x());
        }
      }
    }
  }
  return best;
}

FlapLoads map_loads(Method method, const BeamLine& beam,
                    const std::vector<const WallTrace*>& traces, double width) {
  FlapLoads out = method == Method::linear ? map_linear(beam, traces, width, nullptr)
                                           : map_conservative(beam, traces, width);
  Resultant r = integrate_traces(traces);
  out.traces.force = width * r.force;
  out.traces.moment = width * r.moment;
  out.mapped = nodal_resultant(beam, out.nodal_force, out.nodal_moment);
  return out;
}

FlapLoads map_linear_exact(const BeamLine& beam, const std::vector<const WallTrace*>& traces,
                           double width, const WallField& field) {
  FlapLoads out = map_linear(beam, traces, width, &field);
  out.mapped = nodal_resultant(beam, out.nodal_force, out.nodal_moment);
  return out;
}

}  // namespace tfmb::loads
