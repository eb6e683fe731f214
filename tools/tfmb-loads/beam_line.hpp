// A flap's beam reference line as a polyline of beam nodes, and the projection of wall points
// onto it.
//
// Projection: each element j (nodes a = r_j, b = r_j+1) owns the slab between the node lines
// through a and b; a node line passes through the node normal to the bisector tangent tau of
// the two elements meeting there (the element tangent at the ends). With
// f_a(x) = (x - a).tau_a and f_b(x) = (x - b).tau_b, a point with f_a >= 0 >= f_b lies in
// element j at xi = f_a / (f_a - f_b). On a straight beam this is the orthogonal projection;
// on a curved one it is continuous across nodes (xi = 1 of element j is xi = 0 of j+1), which
// keeps mapped loads and displacements free of jumps. f is linear in x, so the point where a
// straight wall segment crosses a node line is found exactly.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace tfmb::loads {

using Vec2 = Eigen::Vector2d;

// z-component of the planar cross product a x b.
inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

struct BeamProjection {
  std::size_t element = 0;  // element index j (nodes j, j+1)
  double xi = 0.0;          // local coordinate in [0, 1]
  Vec2 point;               // the beam point r_j + xi (r_j+1 - r_j) [m]
  double arc_length = 0.0;  // beam arc length of `point` [m]
  double overshoot = 0.0;   // [m] > 0 if the wall point lies beyond the first or last node line
};

class BeamLine {
 public:
  // Nodes from start to end, at least two, consecutive nodes distinct (throws
  // std::invalid_argument otherwise; callers turn that into a located BadInput).
  explicit BeamLine(std::vector<Vec2> nodes);

  std::size_t node_count() const { return nodes_.size(); }
  std::size_t element_count() const { return nodes_.size() - 1; }
  const std::vector<Vec2>& nodes() const { return nodes_; }
  const std::vector<double>& arc_length() const { return arc_length_; }  // per node [m]
  double length() const { return arc_length_.back(); }
  double element_length(std::size_t j) const { return arc_length_[j + 1] - arc_length_[j]; }
  // Unit bisector tangent at a node.
  const Vec2& node_tangent(std::size_t i) const { return node_tangent_[i]; }
  // Unit tangent of an element and its left normal (tangent rotated +90 degrees).
  Vec2 element_tangent(std::size_t j) const;
  Vec2 element_normal(std::size_t j) const;
  // Signed distance of x from node line i along the node tangent [m].
  double node_line_distance(std::size_t i, const Vec2& x) const {
    return (x - nodes_[i]).dot(node_tangent_[i]);
  }

  BeamProjection project(const Vec2& x) const;

 private:
  std::vector<Vec2> nodes_;
  std::vector<double> arc_length_;
  std::vector<Vec2> node_tangent_;
};

}  // namespace tfmb::loads
