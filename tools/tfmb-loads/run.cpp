#include "run.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>

#include "expression.hpp"
#include "tfmb/common/cli.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/geometry.hpp"
#include "tfmb/common/quadrature.hpp"
#include "tfmb/common/text.hpp"

namespace tfmb::loads {

namespace {

BeamLine make_beam(const ModelFlap& flap, const std::filesystem::path& model_file) {
  try {
    return BeamLine(flap.reference_curve);
  } catch (const std::invalid_argument& e) {
    throw BadInput(model_file.string() + ": /flaps/" + flap.name + "/reference_curve: " + e.what());
  }
}

// Analytic traction fields for --function / --diff.
struct FunctionField {
  std::map<std::string, Expression> fields;
  explicit FunctionField(const std::string& text) {
    const std::vector<std::string> allowed = {"p",       "tau",       "p_inner",
                                              "p_outer", "tau_inner", "tau_outer"};
    std::map<std::string, std::string> assignments;
    try {
      assignments = parse_assignments(text, allowed);
      for (const auto& [name, expr] : assignments)
        fields.emplace(name, Expression(expr, {"x", "y"}));
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--function: ") + e.what());
    }
  }
  double value(const std::string& quantity, Side side, const Vec2& x) const {
    const std::string specific = quantity + (side == Side::inner ? "_inner" : "_outer");
    if (auto it = fields.find(specific); it != fields.end())
      return it->second({x.x(), x.y()});
    if (auto it = fields.find(quantity); it != fields.end())
      return it->second({x.x(), x.y()});
    return 0.0;
  }
};

std::vector<Vec2> refine(const std::vector<Vec2>& line, int pieces) {
  std::vector<Vec2> out;
  for (std::size_t k = 0; k + 1 < line.size(); ++k) {
    for (int p = 0; p < pieces; ++p) {
      out.push_back(line[k] + (static_cast<double>(p) / pieces) * (line[k + 1] - line[k]));
    }
  }
  out.push_back(line.back());
  return out;
}

const std::vector<Vec2>& model_wall(const ModelFlap& flap, Side side) {
  return side == Side::inner ? flap.inner_wall : flap.outer_wall;
}

// A trace on a model wall, oriented away from the opposite wall, with values from `value`.
template <typename Value>
WallTrace model_trace(const ModelFlap& flap, Side side, std::vector<Vec2> points, Value value) {
  WallTrace trace;
  trace.name = flap.name + "_" + side_name(side);
  trace.flap = flap.name;
  trace.side = side;
  trace.points = std::move(points);
  for (const Vec2& x : trace.points) {
    trace.pressure.push_back(value("p", x));
    trace.wall_shear.push_back(value("tau", x));
  }
  check_trace(trace);
  const std::vector<Vec2>& opposite =
      model_wall(flap, side == Side::inner ? Side::outer : Side::inner);
  orient_trace(trace, [&](const Vec2& x) { return closest_point(opposite, x); });
  return trace;
}

void check_coverage(const BeamLine& beam, const ModelFlap& flap, Side side,
                    const std::vector<const WallTrace*>& traces, double tolerance,
                    const std::string& source) {
  const Coverage c = coverage(beam, traces);
  const double allowed = tolerance * beam.length();
  for (const auto& [from, to] : c.gaps) {
    if (to - from > allowed) {
      std::string names;
      for (const WallTrace* t : traces)
        names += (names.empty() ? "" : ", ") + t->name;
      throw BadInput(source + ": /walls/{" + names + "}: the " + side_name(side) +
                     " traces of flap '" + flap.name + "' leave beam arc length [" +
                     text::format_number(from) + ", " + text::format_number(to) + "] m of [0, " +
                     text::format_number(beam.length()) + "] m uncovered (tolerance " +
                     text::format_number(allowed) + " m, --coverage-tolerance)");
    }
  }
}

// Reference distributed loads for --diff: the linear method on the same traces with the field
// evaluated exactly at the wall points facing the beam nodes (so only the trace sampling, or for
// the conservative method the projection, is measured), and the exact totals.
FlapLoads reference_loads(const BeamLine& beam, const ModelFlap& flap, const FunctionField& f,
                          double width, const std::vector<const WallTrace*>& flap_traces) {
  FlapLoads reference = map_linear_exact(beam, flap_traces, width, [&](Side side, const Vec2& x) {
    return std::pair{f.value("p", side, x), f.value("tau", side, x)};
  });
  std::vector<WallTrace> traces;
  for (Side side : {Side::inner, Side::outer}) {
    traces.push_back(model_trace(flap, side, model_wall(flap, side),
                                 [](const std::string&, const Vec2&) { return 0.0; }));
  }
  // Exact totals: five-point Gauss on each model wall segment cut in 64 pieces.
  Resultant exact;
  for (Side side : {Side::inner, Side::outer}) {
    const WallTrace& t = traces[side == Side::inner ? 0 : 1];
    const std::vector<Vec2>& wall = model_wall(flap, side);
    for (std::size_t k = 0; k + 1 < wall.size(); ++k) {
      const Vec2 e = (wall[k + 1] - wall[k]).normalized();
      const Vec2 n = t.normal_sign * Vec2(-e.y(), e.x());
      const double h = (wall[k + 1] - wall[k]).norm() / 64.0;
      for (int piece = 0; piece < 64; ++piece) {
        static const auto gauss_5 = quadrature::gauss_legendre_unit(5);  // on [0, 1]
        for (const auto& [g, w] : gauss_5) {
          const Vec2 x = wall[k] + (piece + g) / 64.0 * (wall[k + 1] - wall[k]);
          const Vec2 traction = -f.value("p", side, x) * n + f.value("tau", side, x) * e;
          exact.force += width * w * h * traction;
          exact.moment += width * w * h * cross(x, traction);
        }
      }
    }
  }
  reference.traces = exact;
  return reference;
}

}  // namespace

ForcesResult run_forces_unchecked(const ForcesOptions& options, const Logger& logger,
                                  std::ostream& out) {
  const Model model = read_model(options.model_file);
  const bool use_function = !options.function.empty();
  if (options.diff && !use_function)
    throw UsageError("--diff needs --function (the exact field)");
  if (use_function && options.function_samples < 1)
    throw UsageError("--samples must be at least 1");
  std::optional<FunctionField> field;
  if (use_function)
    field.emplace(options.function);

  ForcesResult result;
  result.loads.method = options.method;
  std::vector<WallTrace> traces;
  std::string source;
  if (use_function) {
    source = "--function";
    result.loads.header = model.header;
    for (const ModelFlap& flap : model.flaps) {
      for (Side side : {Side::inner, Side::outer}) {
        traces.push_back(model_trace(
            flap, side, refine(model_wall(flap, side), options.function_samples),
            [&](const std::string& q, const Vec2& x) { return field->value(q, side, x); }));
      }
    }
  } else {
    source = options.flow_file.string();
    FlowTraces flow = read_flow_traces(options.flow_file, options.reference_mesh);
    result.loads.header = flow.header;
    traces = std::move(flow.traces);
    for (const auto& name : flow.skipped)
      logger.verbose("wall trace " + name + " belongs to no flap; not mapped");
  }
  result.loads.header.creator = "tfmb-loads " + cli::version();
  if (result.loads.header.geometry != "planar") {
    logger.warn(
        source + ": geometry '" + result.loads.header.geometry +
        "': flap loads are computed as for a planar nozzle (per unit depth times the flap width)");
  }
  result.loads.load_basis =
      "per unit beam length over the flap width (flow traces are per unit depth " +
      text::format_number(result.loads.header.depth) +
      " m and are multiplied by each flap's width)";

  // Every trace must belong to a model flap.
  std::map<std::string, const ModelFlap*> by_name;
  for (const ModelFlap& flap : model.flaps)
    by_name[flap.name] = &flap;
  for (const WallTrace& t : traces) {
    if (!by_name.count(t.flap)) {
      throw BadInput(source + ": /mesh/boundaries/" + t.name + ": flap '" + t.flap +
                     "' is not in " + options.model_file.string());
    }
  }
  // Dry sides loaded by a uniform pressure on request.
  std::vector<WallTrace> extra;
  for (const ModelFlap& flap : model.flaps) {
    for (Side side : {Side::inner, Side::outer}) {
      const bool present = std::any_of(traces.begin(), traces.end(), [&](const WallTrace& t) {
        return t.flap == flap.name && t.side == side;
      });
      if (present)
        continue;
      if (!options.missing_side_pressure) {
        throw BadInput(
            source + ": /walls: flap '" + flap.name + "' has no " + side_name(side) +
            " trace (a wall boundary with flap=" + flap.name + " side=" + side_name(side) +
            "); give --missing-side-pressure to load a dry side with a uniform pressure");
      }
      const double p = *options.missing_side_pressure;
      logger.warn("flap " + flap.name + ": no " + side_name(side) + " trace; uniform pressure " +
                  text::format_number(p) + " Pa on the model's " + side_name(side) + " wall");
      extra.push_back(
          model_trace(flap, side, model_wall(flap, side),
                      [&](const std::string& q, const Vec2&) { return q == "p" ? p : 0.0; }));
    }
  }
  for (auto& t : extra)
    traces.push_back(std::move(t));

  out << "tfmb-loads forces (" << method_name(options.method) << "), loads over the flap width\n";
  out << std::left << std::setw(14) << "flap" << std::right << std::setw(14) << "Fx [N]"
      << std::setw(14) << "Fy [N]" << std::setw(14) << "Mz [N m]" << std::setw(14) << "mapped Fx"
      << std::setw(14) << "mapped Fy" << std::setw(14) << "mapped Mz" << std::setw(12) << "rel.diff"
      << "\n";
  for (const ModelFlap& flap : model.flaps) {
    const BeamLine beam = make_beam(flap, options.model_file);
    std::vector<const WallTrace*> flap_traces;
    LoadsFile::Flap entry;
    entry.name = flap.name;
    entry.width = flap.width;
    for (const WallTrace& t : traces) {
      if (t.flap == flap.name) {
        flap_traces.push_back(&t);
        entry.traces.push_back(t.name);
      }
    }
    // A trace far from its flap's beam is a mislabelled boundary, not a load on this flap.
    const double reach = std::max(10.0 * flap.thickness, 0.1 * beam.length());
    for (const WallTrace* t : flap_traces) {
      for (std::size_t k = 0; k < t->points.size(); ++k) {
        const double distance = (t->points[k] - beam.project(t->points[k]).point).norm();
        if (distance > reach) {
          throw BadInput(source + ": /walls/" + t->name + ": point " + std::to_string(k) +
                         " lies " + text::format_number(distance) + " m from the beam of flap '" +
                         flap.name + "' (more than " + text::format_number(reach) +
                         " m): is the boundary's flap attribute right?");
        }
      }
    }
    for (Side side : {Side::inner, Side::outer}) {
      std::vector<const WallTrace*> side_traces;
      for (const WallTrace* t : flap_traces) {
        if (t->side == side)
          side_traces.push_back(t);
      }
      check_coverage(beam, flap, side, side_traces, options.coverage_tolerance, source);
    }
    entry.nodes = beam.nodes();
    entry.loads = map_loads(options.method, beam, flap_traces, flap.width);
    const FlapLoads& l = entry.loads;
    const double scale_f = std::max(l.traces.force.norm(), 1e-300);
    const double scale_m = std::max(std::abs(l.traces.moment), scale_f * beam.length());
    const double rel = std::max((l.mapped.force - l.traces.force).norm() / scale_f,
                                std::abs(l.mapped.moment - l.traces.moment) / scale_m);
    out << std::left << std::setw(14) << flap.name << std::right << std::setprecision(6)
        << std::setw(14) << l.traces.force.x() << std::setw(14) << l.traces.force.y()
        << std::setw(14) << l.traces.moment << std::setw(14) << l.mapped.force.x() << std::setw(14)
        << l.mapped.force.y() << std::setw(14) << l.mapped.moment << std::setw(12)
        << std::setprecision(3) << rel << "\n";
    if (options.diff) {
      const FlapLoads ref = reference_loads(beam, flap, *field, flap.width, flap_traces);
      FlapDiff d;
      for (std::size_t i = 0; i < beam.node_count(); ++i) {
        d.max_distributed_force_error =
            std::max(d.max_distributed_force_error,
                     (l.distributed_force[i] - ref.distributed_force[i]).norm());
        d.max_distributed_force =
            std::max(d.max_distributed_force, ref.distributed_force[i].norm());
      }
      const double fs = std::max(ref.traces.force.norm(), 1e-300);
      d.force_error = (l.mapped.force - ref.traces.force).norm() / fs;
      d.moment_error = std::abs(l.mapped.moment - ref.traces.moment) /
                       std::max(std::abs(ref.traces.moment), fs * beam.length());
      result.diffs.push_back(d);
    }
    result.loads.flaps.push_back(std::move(entry));
  }
  if (options.diff) {
    out << "mapping error against the function (reference: the field's exact values at the wall "
           "points facing the beam nodes; exact totals by 5-point Gauss on the model walls)\n";
    for (std::size_t f = 0; f < result.diffs.size(); ++f) {
      const FlapDiff& d = result.diffs[f];
      out << "  " << result.loads.flaps[f].name << ": max |q - q_exact| = " << std::setprecision(4)
          << d.max_distributed_force_error << " N/m ("
          << d.max_distributed_force_error / std::max(d.max_distributed_force, 1e-300)
          << " of max |q_exact|), total force error " << d.force_error << ", total moment error "
          << d.moment_error << " (relative)\n";
    }
  }
  formats::Provenance provenance;
  provenance.command_line = options.command_line;
  provenance.settings = options.settings_toml;
  if (!use_function)
    provenance.inputs.push_back(options.flow_file);
  provenance.inputs.push_back(options.model_file);
  write_loads(options.output, result.loads, provenance);
  logger.summary("wrote " + options.output.string() + ": " +
                 std::to_string(result.loads.flaps.size()) + " flaps, method " +
                 method_name(options.method));
  return result;
}

DisplaceResult run_displace_unchecked(const DisplaceOptions& options, const Logger& logger,
                                      std::ostream& out) {
  const Model model = read_model(options.model_file);
  const bool use_function = !options.function.empty();
  if (options.diff && !use_function)
    throw UsageError("--diff needs --function (the exact field)");
  std::map<std::string, Expression> field;
  if (use_function) {
    try {
      for (const auto& [name, expr] : parse_assignments(options.function, {"ux", "uy", "rz"})) {
        field.emplace(name, Expression(expr, {"x", "y"}));
      }
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--function: ") + e.what());
    }
  }
  auto evaluate = [&](const std::string& name, const Vec2& x) {
    auto it = field.find(name);
    return it == field.end() ? 0.0 : it->second({x.x(), x.y()});
  };

  formats::Header header = model.header;
  std::map<std::string, std::pair<BeamLine, BeamMotion>> beams;
  if (use_function) {
    for (const ModelFlap& flap : model.flaps) {
      BeamMotion motion;
      for (const Vec2& r : flap.reference_curve) {
        motion.displacement.emplace_back(evaluate("ux", r), evaluate("uy", r));
        motion.rotation.push_back(evaluate("rz", r));
      }
      beams.emplace(flap.name, std::pair{make_beam(flap, options.model_file), motion});
    }
  } else {
    const Structure structure = read_structure(options.structure_file);
    header = structure.header;
    const std::string sfile = options.structure_file.string();
    for (const auto& [name, sflap] : structure.flaps) {
      if (std::none_of(model.flaps.begin(), model.flaps.end(),
                       [&](const ModelFlap& f) { return f.name == name; })) {
        throw BadInput(sfile + ": /flaps/" + name + ": flap not in " + options.model_file.string() +
                       " (mismatched model and structure files)");
      }
    }
    for (const ModelFlap& flap : model.flaps) {
      auto it = structure.flaps.find(flap.name);
      if (it == structure.flaps.end()) {
        throw BadInput(sfile + ": /flaps: flap '" + flap.name + "' of " +
                       options.model_file.string() +
                       " is missing (mismatched model and structure files)");
      }
      const BeamLine reference = make_beam(flap, options.model_file);
      const double tolerance = options.match_tolerance * reference.length();
      const auto& points = it->second.points;
      // Nodes of higher-order beam elements lie on the curve, not on the chords between the
      // model's beam nodes: compare with the full-resolution reference line where there is one.
      const std::vector<Vec2>& line =
          flap.reference_geometry.size() >= 2 ? flap.reference_geometry : flap.reference_curve;
      for (std::size_t k = 0; k < points.size(); ++k) {
        const double distance =
            std::min((points[k] - closest_point(line, points[k])).norm(),
                     (points[k] - closest_point(flap.reference_curve, points[k])).norm());
        if (distance > tolerance) {
          throw BadInput(sfile + ": /flaps/" + flap.name + "/nodes: beam node " +
                         std::to_string(k) + " at (" + text::format_number(points[k].x()) + ", " +
                         text::format_number(points[k].y()) + ") m lies " +
                         text::format_number(distance) + " m off the reference curve of flap '" +
                         flap.name + "' in " + options.model_file.string() +
                         " (mismatched model and structure files)");
        }
      }
      if ((points.front() - flap.reference_curve.front()).norm() > tolerance ||
          (points.back() - flap.reference_curve.back()).norm() > tolerance) {
        throw BadInput(sfile + ": /flaps/" + flap.name +
                       "/nodes: the beam does not start and end where the "
                       "reference curve of flap '" +
                       flap.name + "' in " + options.model_file.string() +
                       " does (mismatched model and structure files)");
      }
      try {
        beams.emplace(flap.name, std::pair{BeamLine(points), it->second.motion});
      } catch (const std::invalid_argument& e) {
        throw BadInput(sfile + ": /flaps/" + flap.name + "/nodes: " + e.what());
      }
    }
  }
  header.creator = "tfmb-loads " + cli::version();

  DisplaceResult result;
  std::string wall_source;
  if (!options.mesh_file.empty()) {
    wall_source = "mesh wall nodes of " + options.mesh_file.string();
    for (MeshWall& wall : read_mesh_walls(options.mesh_file)) {
      if (!beams.count(wall.flap)) {
        throw BadInput(options.mesh_file.string() + ": /mesh/boundaries/" + wall.name + ": flap '" +
                       wall.flap + "' is not in " + options.model_file.string());
      }
      WallDisplacement d;
      d.name = wall.name;
      d.flap = wall.flap;
      d.side = wall.side;
      d.nodes = std::move(wall.nodes);
      d.points = std::move(wall.points);
      result.walls.push_back(std::move(d));
    }
  } else {
    wall_source = "model walls of " + options.model_file.string();
    for (const ModelFlap& flap : model.flaps) {
      for (Side side : {Side::inner, Side::outer}) {
        WallDisplacement d;
        d.name = flap.name + "_" + side_name(side);
        d.flap = flap.name;
        d.side = side_name(side);
        d.points = model_wall(flap, side);
        result.walls.push_back(std::move(d));
      }
    }
  }
  out << "tfmb-loads displace: wall displacement (" << wall_source << ")\n";
  out << std::left << std::setw(20) << "wall" << std::setw(12) << "flap" << std::right
      << std::setw(8) << "points" << std::setw(16) << "max |d| [m]"
      << (options.diff ? "    max error [m]" : "") << "\n";
  for (WallDisplacement& wall : result.walls) {
    const auto& [beam, motion] = beams.at(wall.flap);
    wall.displacement = wall_displacement(beam, motion, wall.points);
    double largest = 0.0, error = 0.0;
    for (std::size_t i = 0; i < wall.points.size(); ++i) {
      largest = std::max(largest, wall.displacement[i].norm());
      if (options.diff) {
        const Vec2 exact(evaluate("ux", wall.points[i]), evaluate("uy", wall.points[i]));
        error = std::max(error, (wall.displacement[i] - exact).norm());
      }
    }
    if (options.diff)
      result.max_error.push_back(error);
    out << std::left << std::setw(20) << wall.name << std::setw(12) << wall.flap << std::right
        << std::setw(8) << wall.points.size() << std::setw(16) << std::setprecision(6) << largest;
    if (options.diff)
      out << std::setw(17) << std::setprecision(3) << error;
    out << "\n";
  }
  formats::Provenance provenance;
  provenance.command_line = options.command_line;
  provenance.settings = options.settings_toml;
  if (!use_function)
    provenance.inputs.push_back(options.structure_file);
  provenance.inputs.push_back(options.model_file);
  if (!options.mesh_file.empty())
    provenance.inputs.push_back(options.mesh_file);
  write_walldisp(options.output, header, wall_source, result.walls, provenance);
  logger.summary("wrote " + options.output.string() + ": " + std::to_string(result.walls.size()) +
                 " walls");
  return result;
}

ForcesResult run_forces(const ForcesOptions& options, const Logger& logger, std::ostream& out) {
  try {
    return run_forces_unchecked(options, logger, out);
  } catch (const std::invalid_argument& e) {
    // Geometry problems found below the readers (coincident points, a folded beam line).
    throw BadInput(options.model_file.string() + ": " + e.what());
  }
}

DisplaceResult run_displace(const DisplaceOptions& options, const Logger& logger,
                            std::ostream& out) {
  try {
    return run_displace_unchecked(options, logger, out);
  } catch (const std::invalid_argument& e) {
    throw BadInput(options.model_file.string() + ": " + e.what());
  }
}

}  // namespace tfmb::loads
