#include "model_build.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "tfmb/common/cli.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/polyline.hpp"
#include "tfmb/common/text.hpp"

namespace tfmb::input {

using namespace geometry;  // polyline helpers (libcommon)
namespace {

// True if the flap's inner side (facing the nozzle axis) is to the left of its direction.
bool inner_is_left(const Flap& flap) {
  const Point n = mean_left_normal(flap.reference_geometry);
  if (flap.half == "upper") return n.y() < 0.0;
  if (flap.half == "lower") return n.y() > 0.0;
  return false;  // half = none: inner is the right side
}

// Chains a flap's curves end to start (reversing curves as needed).
Polyline chain_curves(const FlapSpec& spec, const std::map<std::string, const Curve*>& by_name,
                      double tolerance, const std::string& case_file) {
  std::vector<const Curve*> curves;
  for (const auto& name : spec.flap.curves) {
    auto it = by_name.find(name);
    if (it == by_name.end()) {
      std::string known;
      for (const auto& [n, c] : by_name) known += (known.empty() ? "" : ", ") + n;
      throw BadInput(case_file + ":" + std::to_string(spec.line) + ": flap '" + spec.flap.name +
                     "': curve '" + name + "' is not in the geometry (curves: " + known + ")");
    }
    curves.push_back(it->second);
  }
  Polyline line = curves[0]->points;
  if (curves.size() > 1) {
    const Polyline& next = curves[1]->points;
    const double d_end = std::min((line.back() - next.front()).norm(), (line.back() - next.back()).norm());
    const double d_start = std::min((line.front() - next.front()).norm(), (line.front() - next.back()).norm());
    if (d_start < d_end) line = reversed(line);
  }
  for (std::size_t k = 1; k < curves.size(); ++k) {
    Polyline next = curves[k]->points;
    if ((line.back() - next.back()).norm() < (line.back() - next.front()).norm()) next = reversed(next);
    const double gap = (line.back() - next.front()).norm();
    if (gap > tolerance) {
      double s = 0.0;
      const bool overlap = distance_to(line, next.front(), &s) <= tolerance ||
                           distance_to(next, line.back(), &s) <= tolerance;
      throw BadInput(std::string(overlap ? "overlap" : "gap") + " of " +
                     text::format_number(gap, 4) + " m between curve '" + curves[k - 1]->name +
                     "' (end at " + format_point(line.back()) + ") and curve '" + curves[k]->name +
                     "' (start at " + format_point(next.front()) + ") in flap '" + spec.flap.name +
                     "' (tolerance " + text::format_number(tolerance, 4) +
                     " m, geometry.tolerance)");
    }
    line.insert(line.end(), next.begin() + 1, next.end());
  }
  // Drop repeated points: they have no direction.
  Polyline clean{line.front()};
  for (std::size_t i = 1; i < line.size(); ++i) {
    if ((line[i] - clean.back()).norm() > 1e-12 * (1.0 + line[i].norm())) clean.push_back(line[i]);
  }
  if (clean.size() < 2) throw BadInput("flap '" + spec.flap.name + "': its curves have zero length");
  return clean;
}

// The curves may draw a surface instead of the mid line: move them to the mid line.
void to_mid_line(const FlapSpec& spec, Flap& flap) {
  if (auto c = self_intersection(flap.reference_geometry)) {
    throw BadInput("self-intersecting wall: flap '" + flap.name + "' (curves " +
                   flap.curves.front() + (flap.curves.size() > 1 ? "..." : "") +
                   ") crosses itself at " + format_point(c->point));
  }
  const double half_t = 0.5 * flap.thickness;
  const double inner_sign = inner_is_left(flap) ? 1.0 : -1.0;
  if (spec.reference == "inner") flap.reference_geometry = offset(flap.reference_geometry, -inner_sign * half_t);
  if (spec.reference == "outer") flap.reference_geometry = offset(flap.reference_geometry, inner_sign * half_t);
}

void build_flap(Flap& flap, const Logger& log) {
  const double half_t = 0.5 * flap.thickness;
  const bool left = inner_is_left(flap);
  const double inner_sign = left ? 1.0 : -1.0;
  flap.inner_wall = offset(flap.reference_geometry, inner_sign * half_t);
  flap.outer_wall = offset(flap.reference_geometry, -inner_sign * half_t);
  for (const auto* wall : {&flap.inner_wall, &flap.outer_wall}) {
    if (auto c = self_intersection(*wall)) {
      throw BadInput("self-intersecting wall: the " +
                     std::string(wall == &flap.inner_wall ? "inner" : "outer") +
                     " surface of flap '" + flap.name + "' folds at " + format_point(c->point) +
                     ": thickness " + text::format_number(flap.thickness, 4) +
                     " m is too large for the curvature there");
    }
  }
  const auto s = geometry::cumulative_length(flap.reference_geometry);
  flap.inner_wall_s = s;
  flap.outer_wall_s = s;
  flap.reference_curve = resample(flap.reference_geometry, flap.elements);
  Polyline outline = flap.inner_wall;
  const Polyline back = reversed(flap.outer_wall);
  outline.insert(outline.end(), back.begin(), back.end());
  if (geometry::signed_area(outline) < 0.0) outline = reversed(outline);
  flap.solid_outline = outline;
  if (flap.section.kind == "rectangle") {
    flap.section = rectangle_section(flap.thickness, flap.width, flap.section.youngs_modulus,
                                     flap.section.poisson_ratio, flap.section.density);
  }
  const double len = length(flap.reference_geometry);
  if (len > 50.0 || len < 1e-3) {
    log.warn("flap '" + flap.name + "' is " + text::format_number(len, 4) +
             " m long: check geometry.scale (units)");
  }
  if (flap.thickness > 0.25 * len) {
    log.warn("flap '" + flap.name + "' thickness " + text::format_number(flap.thickness, 4) +
             " m is more than a quarter of its length " + text::format_number(len, 4) +
             " m: a beam model is doubtful; check units");
  }
}

Point end_point(const Flap& f, const std::string& end) {
  return end == "start" ? f.reference_geometry.front() : f.reference_geometry.back();
}

void build_joint(const JointSpec& spec, Joint& joint, const Model& model, double tolerance,
                 const std::string& case_file) {
  const std::string where = case_file + ":" + std::to_string(spec.line) + ": joint '" + joint.name + "'";
  const Flap* a = model.find_flap(joint.flap_a);
  const Flap* b = model.find_flap(joint.flap_b);
  if (!a) throw BadInput(where + ": unknown flap '" + joint.flap_a + "'");
  if (!b) throw BadInput(where + ": unknown flap '" + joint.flap_b + "'");
  if (a == b) throw BadInput(where + ": joins flap '" + a->name + "' to itself");
  static const char* ends[] = {"start", "end"};
  if (spec.point) {
    joint.point = *spec.point;
    for (auto [flap, end] : {std::pair{a, &joint.end_a}, std::pair{b, &joint.end_b}}) {
      const double ds = (end_point(*flap, "start") - joint.point).norm();
      const double de = (end_point(*flap, "end") - joint.point).norm();
      *end = ds <= de ? "start" : "end";
      if (std::min(ds, de) > tolerance) {
        throw BadInput(where + " at " + format_point(joint.point) + " is not at an end of flap '" +
                       flap->name + "' (nearest end '" + *end + "' at " +
                       format_point(end_point(*flap, *end)) + ", " +
                       text::format_number(std::min(ds, de), 4) + " m away; tolerance " +
                       text::format_number(tolerance, 4) + " m)");
      }
    }
    return;
  }
  double best = std::numeric_limits<double>::infinity();
  for (const char* ea : ends) {
    for (const char* eb : ends) {
      const double d = (end_point(*a, ea) - end_point(*b, eb)).norm();
      if (d < best) {
        best = d;
        joint.end_a = ea;
        joint.end_b = eb;
      }
    }
  }
  const Point pa = end_point(*a, joint.end_a), pb = end_point(*b, joint.end_b);
  joint.point = 0.5 * (pa + pb);
  if (best > tolerance) {
    const bool overlap = distance_to(b->reference_geometry, pa) <= tolerance ||
                         distance_to(a->reference_geometry, pb) <= tolerance;
    throw BadInput(std::string(overlap ? "overlap" : "gap") + " of " +
                   text::format_number(best, 4) + " m at " + where + ": curve '" +
                   (joint.end_a == "start" ? a->curves.front() : a->curves.back()) + "' of flap '" +
                   a->name + "' ends at " + format_point(pa) + ", curve '" +
                   (joint.end_b == "start" ? b->curves.front() : b->curves.back()) + "' of flap '" +
                   b->name + "' at " + format_point(pb) + " (tolerance " +
                   text::format_number(tolerance, 4) + " m, geometry.tolerance)");
  }
}

// Flaps must not cross one another except at the joints that connect them.
void check_overlaps(const Model& model, double tolerance) {
  for (std::size_t i = 0; i < model.flaps.size(); ++i) {
    for (std::size_t k = i + 1; k < model.flaps.size(); ++k) {
      const Flap& a = model.flaps[i];
      const Flap& b = model.flaps[k];
      std::vector<Point> joints;
      for (const Joint& j : model.joints) {
        if ((j.flap_a == a.name && j.flap_b == b.name) || (j.flap_a == b.name && j.flap_b == a.name)) {
          joints.push_back(j.point);
        }
      }
      const double radius = std::max(10.0 * tolerance, 0.5 * std::max(a.thickness, b.thickness));
      if (auto c = crossing(a.reference_geometry, b.reference_geometry, joints, radius)) {
        throw BadInput("overlap: flap '" + a.name + "' (curve '" + a.curves.front() + "') and flap '" +
                       b.name + "' (curve '" + b.curves.front() + "') cross at " +
                       format_point(c->point) + " away from any joint between them");
      }
    }
  }
}

// --- flow domain -------------------------------------------------------------------------

struct ChainPiece {
  const Flap* flap;
  bool forward;  // flap direction equals chain direction
};

// The flaps of one half in order from the upstream free end.
std::vector<ChainPiece> half_chain(const Model& model, const std::string& half) {
  std::vector<const Flap*> flaps;
  for (const Flap& f : model.flaps) {
    if (f.half == half) flaps.push_back(&f);
  }
  if (flaps.empty()) throw BadInput("domain.kind = 'nozzle' needs flaps with half = '" + half + "'");
  auto joined = [&](const Flap* f, const std::string& end) -> const Joint* {
    for (const Joint& j : model.joints) {
      if ((j.flap_a == f->name && j.end_a == end) || (j.flap_b == f->name && j.end_b == end)) return &j;
    }
    return nullptr;
  };
  // Start: the free flap end with the smallest x.
  const Flap* first = nullptr;
  std::string first_end;
  double best_x = std::numeric_limits<double>::infinity();
  for (const Flap* f : flaps) {
    for (const char* end : {"start", "end"}) {
      if (!joined(f, end) && end_point(*f, end).x() < best_x) {
        best_x = end_point(*f, end).x();
        first = f;
        first_end = end;
      }
    }
  }
  if (!first) throw BadInput("the " + half + " flaps form a closed loop: a nozzle half needs a free upstream end");
  std::vector<ChainPiece> chain;
  const Flap* current = first;
  std::string entry = first_end;
  while (current) {
    chain.push_back({current, entry == "start"});
    const std::string exit = entry == "start" ? "end" : "start";
    const Joint* j = joined(current, exit);
    if (!j) break;
    const bool a_side = j->flap_a == current->name && j->end_a == exit;
    const Flap* next = model.find_flap(a_side ? j->flap_b : j->flap_a);
    entry = a_side ? j->end_b : j->end_a;
    if (next->half != half) {
      throw BadInput("joint '" + j->name + "' connects flap '" + current->name + "' (" + half +
                     ") to flap '" + next->name + "' (" + next->half + ")");
    }
    current = next;
    if (chain.size() > model.flaps.size()) throw BadInput("the " + half + " flaps form a loop");
  }
  if (chain.size() != flaps.size()) {
    throw BadInput("the " + half + " flaps are not one chain joined end to end (" +
                   std::to_string(chain.size()) + " of " + std::to_string(flaps.size()) +
                   " reached from flap '" + first->name + "'): add joints");
  }
  return chain;
}

struct SidePiece {
  const Flap* flap;
  std::string side;
  Polyline points;  // chain direction
};

// The offset of a chain on its left (side = +1) or right (-1), joined at flap junctions by
// trimming (concave) or a circular arc about the joint (convex).
std::vector<SidePiece> chain_side(const std::vector<ChainPiece>& chain, double side) {
  std::vector<SidePiece> pieces;
  for (const ChainPiece& c : chain) {
    const bool on_left_of_flap = (side > 0) == c.forward;
    const bool inner_left = inner_is_left(*c.flap);
    Polyline wall = (on_left_of_flap == inner_left) ? c.flap->inner_wall : c.flap->outer_wall;
    if (!c.forward) wall = reversed(wall);
    pieces.push_back({c.flap, on_left_of_flap == inner_left ? "inner" : "outer", wall});
  }
  for (std::size_t k = 0; k + 1 < pieces.size(); ++k) {
    Polyline& a = pieces[k].points;
    Polyline& b = pieces[k + 1].points;
    const Point joint = chain[k].forward ? chain[k].flap->reference_geometry.back()
                                         : chain[k].flap->reference_geometry.front();
    bool trimmed = false;
    const std::size_t reach = 12;
    for (std::size_t i = a.size() - 1; i-- > (a.size() > reach ? a.size() - reach - 1 : 0) && !trimmed;) {
      for (std::size_t j = 0; j + 1 < std::min(b.size(), reach + 1) && !trimmed; ++j) {
        if (auto p = geometry::segment_intersection(a[i], a[i + 1], b[j], b[j + 1])) {
          a.resize(i + 1);
          a.push_back(*p);
          b.erase(b.begin(), b.begin() + static_cast<std::ptrdiff_t>(j + 1));
          b.insert(b.begin(), *p);
          trimmed = true;
        }
      }
    }
    if (trimmed) continue;
    const Point ra = a.back() - joint, rb = b.front() - joint;
    const double angle = std::atan2(ra.x() * rb.y() - ra.y() * rb.x(), ra.dot(rb));
    const int steps = std::max(2, static_cast<int>(std::ceil(std::abs(angle) / (M_PI / 12.0))));
    Polyline arc;
    const double a0 = std::atan2(ra.y(), ra.x());
    for (int s = 1; s < steps; ++s) {
      const double f = static_cast<double>(s) / steps;
      const double r = (1.0 - f) * ra.norm() + f * rb.norm();
      arc.push_back(joint + r * Point(std::cos(a0 + f * angle), std::sin(a0 + f * angle)));
    }
    const std::size_t half = arc.size() / 2;
    a.insert(a.end(), arc.begin(), arc.begin() + static_cast<std::ptrdiff_t>(half + 1));
    b.insert(b.begin(), arc.begin() + static_cast<std::ptrdiff_t>(half), arc.end());
  }
  return pieces;
}

DomainBoundary piece(std::string name, std::string kind, Polyline points, std::string flap = "",
                     std::string side = "") {
  return {std::move(name), std::move(kind), std::move(flap), std::move(side), std::move(points)};
}

Polyline segment(const Point& a, const Point& b) { return {a, b}; }

void append_reversed(std::vector<DomainBoundary>& loop, std::vector<SidePiece> pieces) {
  for (auto it = pieces.rbegin(); it != pieces.rend(); ++it) {
    loop.push_back(piece(it->flap->name + "_" + it->side, "wall", reversed(it->points), it->flap->name, it->side));
  }
}
void append_forward(std::vector<DomainBoundary>& loop, const std::vector<SidePiece>& pieces) {
  for (const auto& p : pieces) loop.push_back(piece(p.flap->name + "_" + p.side, "wall", p.points, p.flap->name, p.side));
}

std::vector<DomainBoundary> nozzle_domain(const Model& model) {
  const DomainSettings& d = model.domain.settings;
  const auto upper = half_chain(model, "upper");
  const auto lower = half_chain(model, "lower");
  double x_min = std::numeric_limits<double>::infinity(), x_max = -x_min, y_abs = 0.0;
  for (const Flap& f : model.flaps) {
    for (const auto* wall : {&f.inner_wall, &f.outer_wall}) {
      for (const Point& p : *wall) {
        x_min = std::min(x_min, p.x());
        x_max = std::max(x_max, p.x());
        y_abs = std::max(y_abs, std::abs(p.y()));
      }
    }
  }
  const double x_up = x_min - d.plenum_length;
  const double x_down = x_max + d.downstream_length;
  const double height = d.farfield_height;
  if (height <= 1.2 * y_abs) {
    throw BadInput("domain.farfield_height = " + text::format_number(height, 4) +
                   " m must clearly exceed the nozzle's largest |y| = " +
                   text::format_number(y_abs, 4) + " m");
  }
  // Upper chain: internal flow on its right (-1); lower chain: on its left (+1).
  const auto upper_int = chain_side(upper, -1.0), upper_ext = chain_side(upper, +1.0);
  const auto lower_int = chain_side(lower, +1.0), lower_ext = chain_side(lower, -1.0);
  const Flap& upper_last = *upper.back().flap;
  const Flap& lower_last = *lower.back().flap;
  const std::string end_side = "end";

  std::vector<DomainBoundary> loop;
  loop.push_back(piece("farfield_lower", "farfield", segment({x_up, -height}, {x_down, -height})));
  // The downstream face of the plume box is ambient air too: a characteristic far field lets the
  // jet leave (supersonic parts extrapolated) and the entrained air come in, where a fixed static
  // pressure with interior entropy on backflow drives the corners to vacuum (tfmb-flow README).
  loop.push_back(piece("farfield_downstream", "farfield", segment({x_down, -height}, {x_down, height})));
  loop.push_back(piece("farfield_upper", "farfield", segment({x_down, height}, {x_up, height})));
  // Upper body, travelled with the flow domain on the left.
  const Point upper_int_start = upper_int.front().points.front();
  Point upper_outer_start;
  if (!d.boattail) {
    upper_outer_start = upper_ext.front().points.front();
    loop.push_back(piece("farfield_left_upper", "farfield", segment({x_up, height}, {x_up, upper_outer_start.y()})));
    loop.push_back(piece("upper_nacelle", "wall", segment({x_up, upper_outer_start.y()}, upper_outer_start)));
    append_forward(loop, upper_ext);
    loop.push_back(piece(upper_last.name + "_end", "wall",
                         segment(upper_ext.back().points.back(), upper_int.back().points.back()),
                         upper_last.name, end_side));
    append_reversed(loop, upper_int);
  } else {
    upper_outer_start = upper_int.back().points.back();
    loop.push_back(piece("farfield_left_upper", "farfield", segment({x_up, height}, {x_up, upper_outer_start.y()})));
    loop.push_back(piece("upper_nacelle", "wall", segment({x_up, upper_outer_start.y()}, upper_outer_start)));
    append_reversed(loop, upper_int);
  }
  loop.push_back(piece("upper_plenum", "wall", segment(upper_int_start, {x_up, upper_int_start.y()})));
  const Point lower_int_start = lower_int.front().points.front();
  loop.push_back(piece("inflow", "inflow", segment({x_up, upper_int_start.y()}, {x_up, lower_int_start.y()})));
  loop.push_back(piece("lower_plenum", "wall", segment({x_up, lower_int_start.y()}, lower_int_start)));
  Point lower_outer_start;
  if (!d.boattail) {
    append_forward(loop, lower_int);
    loop.push_back(piece(lower_last.name + "_end", "wall",
                         segment(lower_int.back().points.back(), lower_ext.back().points.back()),
                         lower_last.name, end_side));
    append_reversed(loop, lower_ext);
    lower_outer_start = lower_ext.front().points.front();
  } else {
    append_forward(loop, lower_int);
    lower_outer_start = lower_int.back().points.back();
  }
  loop.push_back(piece("lower_nacelle", "wall", segment(lower_outer_start, {x_up, lower_outer_start.y()})));
  loop.push_back(piece("farfield_left_lower", "farfield", segment({x_up, lower_outer_start.y()}, {x_up, -height})));
  if (upper_int_start.y() <= lower_int_start.y()) {
    throw BadInput("the upper flaps start below the lower flaps (" + format_point(upper_int_start) + " vs " +
                   format_point(lower_int_start) + "): check half = upper/lower");
  }
  return loop;
}

std::vector<DomainBoundary> channel_domain(const Model& model, const std::vector<Curve>& curves) {
  const std::string& name = model.domain.settings.wall_curve;
  const Curve* wall = nullptr;
  for (const Curve& c : curves) {
    if (c.name == name) wall = &c;
  }
  if (!wall) throw BadInput("domain.wall_curve = '" + name + "' is not a curve of the geometry file");
  Polyline w = wall->points;
  if (w.front().x() > w.back().x()) w = reversed(w);
  for (std::size_t i = 1; i < w.size(); ++i) {
    if (w[i].x() <= w[i - 1].x()) {
      throw BadInput("domain.wall_curve '" + name + "': x must increase along the channel wall (at " +
                     format_point(w[i]) + ")");
    }
    if (w[i].y() <= 0.0) throw BadInput("domain.wall_curve '" + name + "' must lie above the axis y = 0 (at " + format_point(w[i]) + ")");
  }
  const Point a = w.front(), b = w.back();
  std::vector<DomainBoundary> loop;
  // Axisymmetric: the lower line is the axis of revolution (tfmb-flow's `axis` kind).
  const std::string lower = model.geometry == "axisymmetric" ? "axis" : "symmetry";
  loop.push_back(piece(lower, lower, segment({a.x(), 0.0}, {b.x(), 0.0})));
  loop.push_back(piece("outflow", "outflow", segment({b.x(), 0.0}, b)));
  loop.push_back(piece("wall", "wall", reversed(w)));
  loop.push_back(piece("inflow", "inflow", segment(a, {a.x(), 0.0})));
  return loop;
}

std::vector<DomainBoundary> flatplate_domain(const DomainSettings& d) {
  const double u = d.upstream_length, l = d.plate_length, h = d.farfield_height;
  std::vector<DomainBoundary> loop;
  if (u > 0.0) loop.push_back(piece("symmetry", "symmetry", segment({-u, 0.0}, {0.0, 0.0})));
  loop.push_back(piece("plate", "wall", segment({0.0, 0.0}, {l, 0.0})));
  loop.push_back(piece("outflow", "outflow", segment({l, 0.0}, {l, h})));
  loop.push_back(piece("farfield", "farfield", segment({l, h}, {-u, h})));
  loop.push_back(piece("inflow", "inflow", segment({-u, h}, {-u, 0.0})));
  return loop;
}

void check_domain(const std::vector<DomainBoundary>& loop) {
  for (std::size_t i = 0; i < loop.size(); ++i) {
    if (auto c = self_intersection(loop[i].points)) {
      throw BadInput("self-intersecting wall: flow boundary '" + loop[i].name + "' crosses itself at " +
                     format_point(c->point));
    }
    for (std::size_t k = i + 1; k < loop.size(); ++k) {
      const bool adjacent = k == i + 1 || (i == 0 && k == loop.size() - 1);
      std::vector<Point> shared;
      if (adjacent) shared = {k == i + 1 ? loop[i].points.back() : loop[i].points.front()};
      const Polyline& a = loop[i].points;
      const Polyline& b = loop[k].points;
      const double scale = 1e-9 * (1.0 + length(a) + length(b));
      if (auto c = crossing(a, b, shared, scale)) {
        throw BadInput("self-intersecting wall: flow boundary '" + loop[i].name + "' crosses '" +
                       loop[k].name + "' at " + format_point(c->point) +
                       " (flaps too thick, joints misplaced, or domain extents too small)");
      }
    }
  }
  Polyline closed;
  for (const auto& b : loop) closed.insert(closed.end(), b.points.begin(), b.points.end() - 1);
  if (geometry::signed_area(closed) <= 0.0) {
    throw InternalError("flow domain loop is not counter-clockwise");
  }
}

}  // namespace

Domain build_domain(const Model& model, const std::vector<Curve>& curves) {
  Domain domain;
  domain.settings = model.domain.settings;
  const std::string& kind = domain.settings.kind;
  if (kind == "nozzle") domain.boundaries = nozzle_domain(model);
  else if (kind == "channel") domain.boundaries = channel_domain(model, curves);
  else if (kind == "flatplate") domain.boundaries = flatplate_domain(domain.settings);
  if (!domain.boundaries.empty()) check_domain(domain.boundaries);
  return domain;
}

Model build_model(const CaseSpec& spec, const std::vector<Curve>& curves, const Logger& log) {
  Model model = spec.settings;
  const std::string case_file = spec.file.string();
  const double tol = spec.geometry.tolerance;
  std::map<std::string, const Curve*> by_name;
  for (const Curve& c : curves) {
    if (!by_name.emplace(c.name, &c).second) {
      throw BadInput(spec.geometry.file.string() + ": two curves are named '" + c.name + "'");
    }
  }
  for (const FlapSpec& fs : spec.flaps) {
    if (model.find_flap(fs.flap.name)) {
      throw BadInput(case_file + ":" + std::to_string(fs.line) + ": two flaps are named '" + fs.flap.name + "'");
    }
    Flap flap = fs.flap;
    flap.reference_geometry = chain_curves(fs, by_name, tol, case_file);
    model.flaps.push_back(std::move(flap));
  }
  // Joints are checked on the curves as drawn; then curves drawing a surface move to the mid
  // line and the flap ends at each joint are made to coincide again (their offsets differ by
  // the tiny difference of the end tangents).
  for (JointSpec js : spec.joints) {
    if (js.point) *js.point *= spec.geometry.scale;  // given in geometry units
    Joint joint = js.joint;
    build_joint(js, joint, model, tol, case_file);
    for (const Joint& other : model.joints) {
      if (other.name == joint.name) throw BadInput(case_file + ":" + std::to_string(js.line) + ": two joints are named '" + joint.name + "'");
    }
    model.joints.push_back(joint);
  }
  for (std::size_t i = 0; i < model.flaps.size(); ++i) to_mid_line(spec.flaps[i], model.flaps[i]);
  auto end_ref = [&](const std::string& flap, const std::string& end) -> Point& {
    for (Flap& f : model.flaps) {
      if (f.name == flap) return end == "start" ? f.reference_geometry.front() : f.reference_geometry.back();
    }
    throw InternalError("unknown flap " + flap);
  };
  for (Joint& j : model.joints) {
    Point& a = end_ref(j.flap_a, j.end_a);
    Point& b = end_ref(j.flap_b, j.end_b);
    const Point mid = 0.5 * (a + b);
    if ((a - b).norm() > 0.05 * std::max(model.find_flap(j.flap_a)->thickness, model.find_flap(j.flap_b)->thickness) + tol) {
      throw BadInput("joint '" + j.name + "': the flaps' mid lines end " + std::to_string((a - b).norm()) +
                     " m apart after moving the drawn surfaces by half the thickness (the flaps meet at an angle): "
                     "draw the mid lines (flap reference = \"mid\")");
    }
    a = mid;
    b = mid;
    j.point = mid;
  }
  for (Flap& flap : model.flaps) build_flap(flap, log);
  for (const SupportSpec& ss : spec.supports) {
    Support support = ss.support;
    const Flap* flap = model.find_flap(support.flap);
    if (!flap) {
      throw BadInput(case_file + ":" + std::to_string(ss.line) + ": support '" + support.name +
                     "': unknown flap '" + support.flap + "'");
    }
    support.point = end_point(*flap, support.end);
    if (support.slides() && support.axis.isZero()) {
      // Default sliding direction: the flap's own at that end (its beam's end segment), the
      // direction in which a hot flap grows.
      const Polyline& c = flap->reference_curve;
      const Point d =
          support.end == "start" ? Point(c[1] - c[0]) : Point(c[c.size() - 1] - c[c.size() - 2]);
      support.axis = d.normalized();
    }
    model.supports.push_back(support);
  }
  check_overlaps(model, tol);
  model.domain = build_domain(model, curves);
  model.flow.viscous_length = viscous_length(model.flow);
  if (model.flow.yplus_target > 0.0) {
    if (model.flow.viscous_length <= 0.0)
      throw BadInput(spec.file.string() +
                     ": flow.yplus_target: the flow conditions give no y+ estimate "
                     "(stagnation temperature, pressures and gamma must describe a flow); give "
                     "flow.first_cell_height instead");
    model.flow.first_cell_height = model.flow.yplus_target * model.flow.viscous_length;
  }
  return model;
}

void run(const Options& options, const Logger& log) {
  Stopwatch clock;
  const CaseSpec spec = read_case(options.case_file, options.overrides);
  std::vector<Curve> curves;
  if (!spec.geometry.file.empty()) {
    curves = read_geometry(spec.geometry.file, spec.geometry.scale, spec.geometry.curve_samples);
    log.verbose("read " + std::to_string(curves.size()) + " curves from " + spec.geometry.file.string());
    if (!options.curves_csv.empty()) write_curves_csv(curves, options.curves_csv);
  } else if (!spec.flaps.empty() || spec.settings.domain.settings.kind == "channel") {
    throw BadInput(options.case_file.string() + ": flaps need a [geometry] table with a file");
  }
  const Model model = build_model(spec, curves, log);
  formats::Provenance provenance;
  provenance.command_line = options.command_line;
  provenance.settings = spec.resolved_toml;
  provenance.inputs = {options.case_file};
  if (!spec.geometry.file.empty()) provenance.inputs.push_back(spec.geometry.file);
  write_model(model, options.output, "tfmb-input " + cli::version(), provenance);
  log.summary("wrote " + options.output.string() + ": " + std::to_string(model.flaps.size()) +
              " flaps, " + std::to_string(model.joints.size()) + " joints, " +
              std::to_string(model.supports.size()) + " supports, " +
              std::to_string(model.domain.boundaries.size()) + " domain boundaries, first cell " +
              text::format_number(model.flow.first_cell_height, 4) + " m (" +
              text::format_number(clock.seconds(), 4) + " s)");
}

}  // namespace tfmb::input
