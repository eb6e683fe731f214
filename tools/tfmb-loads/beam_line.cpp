#include "beam_line.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace tfmb::loads {

BeamLine::BeamLine(std::vector<Vec2> nodes) : nodes_(std::move(nodes)) {
  if (nodes_.size() < 2) throw std::invalid_argument("a beam line needs at least two nodes");
  arc_length_.assign(nodes_.size(), 0.0);
  for (std::size_t i = 1; i < nodes_.size(); ++i) {
    const double h = (nodes_[i] - nodes_[i - 1]).norm();
    if (!(h > 0.0)) {
      throw std::invalid_argument("beam nodes " + std::to_string(i - 1) + " and " +
                                  std::to_string(i) + " coincide");
    }
    arc_length_[i] = arc_length_[i - 1] + h;
  }
  node_tangent_.resize(nodes_.size());
  node_tangent_.front() = element_tangent(0);
  node_tangent_.back() = element_tangent(element_count() - 1);
  for (std::size_t i = 1; i + 1 < nodes_.size(); ++i) {
    const Vec2 sum = element_tangent(i - 1) + element_tangent(i);
    if (!(sum.norm() > 1e-12)) throw std::invalid_argument("beam line folds back on itself");
    node_tangent_[i] = sum.normalized();
  }
  if (nodes_.size() >= 3) {
    // End tangents: the neighbour's bisector tangent reflected about the end chord, i.e. the
    // tangent of the circle through the three end nodes. The chord direction itself would be
    // off by half the turn of the end element, a first-order error in where the end node line
    // meets the walls.
    auto reflect = [](const Vec2& chord, const Vec2& tangent) {
      return Vec2(2.0 * chord.dot(tangent) * chord - tangent);
    };
    node_tangent_.front() = reflect(element_tangent(0), node_tangent_[1]).normalized();
    const std::size_t last = nodes_.size() - 1;
    node_tangent_.back() = reflect(element_tangent(last - 1), node_tangent_[last - 1]).normalized();
  }
}

Vec2 BeamLine::element_tangent(std::size_t j) const {
  return (nodes_[j + 1] - nodes_[j]).normalized();
}

Vec2 BeamLine::element_normal(std::size_t j) const {
  const Vec2 t = element_tangent(j);
  return {-t.y(), t.x()};
}

BeamProjection BeamLine::project(const Vec2& x) const {
  BeamProjection best;
  double best_distance = std::numeric_limits<double>::infinity();
  bool found = false;
  const std::size_t last = element_count() - 1;
  for (std::size_t j = 0; j <= last; ++j) {
    double fa = node_line_distance(j, x);
    double fb = node_line_distance(j + 1, x);
    double overshoot = 0.0;
    // Points before the first or after the last node line belong to the end elements.
    if (j == 0 && fa < 0.0) {
      overshoot = -fa;
      fa = 0.0;
    }
    if (j == last && fb > 0.0) {
      overshoot = fb;
      fb = 0.0;
    }
    if (fa < 0.0 || fb > 0.0) continue;
    const double denominator = fa - fb;
    const double xi = denominator > 0.0 ? fa / denominator : 0.0;
    const Vec2 point = nodes_[j] + xi * (nodes_[j + 1] - nodes_[j]);
    // On a curved line, far-away node lines cross; the nearest candidate is the right one.
    const double distance = (x - point).norm();
    if (!found || distance < best_distance) {
      found = true;
      best_distance = distance;
      best.element = j;
      best.xi = xi;
      best.point = point;
      best.arc_length = arc_length_[j] + xi * element_length(j);
      best.overshoot = overshoot;
    }
  }
  if (!found) throw std::invalid_argument("point cannot be projected onto the beam line");
  return best;
}

}  // namespace tfmb::loads
