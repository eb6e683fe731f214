#include "run.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numeric>
#include <optional>
#include <stdexcept>

#include "quasi_one_dimensional.hpp"
#include "tfmb/common/cli.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/common/log.hpp"
#include "tfmb/common/options.hpp"
#include "tfmb/common/text.hpp"
#include "tfmb/formats/files.hpp"
#include "tfmb/formats/flow.hpp"
#include "tfmb/formats/flowmesh.hpp"
#include "tfmb/formats/schema.hpp"

namespace tfmb::flow {

namespace {

// For a run that did not converge: the last row of the residual history (each equation's
// residual over its largest in this run, as /convergence/residual_history holds it, and the
// turbulence equation's likewise), the equation furthest from converged and where its residual
// per volume is largest. A run stopped with its density down 8 orders may still have a
// turbulence equation or an energy residual that stalled.
// Each equation's largest residual over the history (the mean flow's four, then the turbulence
// equation's): the reference of /convergence/residual_history.
std::array<double, 5> largest_residuals(const std::vector<IterationRecord>& history) {
  std::array<double, 5> largest{};
  for (const IterationRecord& rec : history) {
    for (int v = 0; v < 4; ++v)
      largest[v] = std::max(largest[v], rec.residual[v]);
    largest[4] = std::max(largest[4], rec.turbulence_residual);
  }
  return largest;
}

std::string equation_drops_text(const SolveReport& rep, bool turbulent, TurbulenceModel model) {
  if (rep.history.empty())
    return "no iteration";
  const int equations = turbulent ? 5 : 4;
  const std::array<double, 5> largest = largest_residuals(rep.history);
  const IterationRecord& last = rep.history.back();
  std::array<double, 5> drop{};
  int furthest = 0;
  for (int v = 0; v < equations; ++v) {
    const double r = v < 4 ? last.residual[v] : last.turbulence_residual;
    drop[v] = largest[v] > 0.0 ? r / largest[v] : 0.0;
    if (drop[v] > drop[furthest])
      furthest = v;
  }
  const char* names[5] = {"density", "x-momentum", "y-momentum", "energy",
                          model == TurbulenceModel::sst ? "k" : "nu_tilde"};
  std::string text = "residuals against their largest:";
  for (int v = 0; v < equations; ++v)
    text += std::string(v > 0 ? "," : "") + " " + names[v] + " " + text::format_number(drop[v], 3);
  const Vec2& at = rep.largest_residual_at[furthest];
  return text + "; furthest from converged: " + names[furthest] + ", largest at (" +
         text::format_number(at.x) + ", " + text::format_number(at.y) + ") m" +
         (furthest == 4 && model == TurbulenceModel::sst ? " (the density's largest)" : "");
}

struct LoadedMesh {
  Mesh mesh;
  formats::Mesh file_mesh;         // as read
  std::vector<std::string> kinds;  // per mesh.boundaries
  Geometry geometry = Geometry::planar;
  double depth = 1.0;
};

LoadedMesh load_mesh(const std::filesystem::path& file) {
  formats::FlowMesh in = formats::read_flowmesh(file);
  LoadedMesh out;
  out.geometry = in.header.geometry == "axisymmetric" ? Geometry::axisymmetric : Geometry::planar;
  out.depth = in.header.depth;
  out.file_mesh = std::move(in.mesh);
  const auto& fm = out.file_mesh;
  Mesh& m = out.mesh;
  m.points.resize(fm.node_count());
  for (std::size_t i = 0; i < fm.node_count(); ++i)
    m.points[i] = {fm.points(i, 0), fm.points(i, 1)};
  for (Eigen::Index r = 0; r < fm.triangles.rows(); ++r) {
    m.triangles.push_back({static_cast<int>(fm.triangles(r, 0)),
                           static_cast<int>(fm.triangles(r, 1)),
                           static_cast<int>(fm.triangles(r, 2))});
  }
  for (Eigen::Index r = 0; r < fm.quads.rows(); ++r) {
    m.quads.push_back({static_cast<int>(fm.quads(r, 0)), static_cast<int>(fm.quads(r, 1)),
                       static_cast<int>(fm.quads(r, 2)), static_cast<int>(fm.quads(r, 3))});
  }
  for (const auto& [name, b] : fm.boundaries) {
    if (b.kind.rfind("solid_", 0) == 0) {
      in.fail("/mesh/boundaries/" + name,
              "kind '" + b.kind + "' belongs to a solid mesh; give tfmb-flow the flow mesh");
    }
    BoundaryCurve c{name, {}};
    for (Eigen::Index r = 0; r < b.edges.rows(); ++r) {
      c.edges.push_back({static_cast<int>(b.edges(r, 0)), static_cast<int>(b.edges(r, 1))});
    }
    m.boundaries.push_back(std::move(c));
    out.kinds.push_back(b.kind);
  }
  try {
    check_mesh(m);
  } catch (const std::invalid_argument& e) {
    in.fail("/mesh", e.what());
  }
  return out;
}

// The state of an earlier run on a mesh of the same topology (--restart): its node states (the
// reader refused non-physical ones) and, where it has them, nu_tilde and the residual reference.
formats::Flow read_restart(const std::filesystem::path& file, const LoadedMesh& lm) {
  formats::Flow restart = formats::read_flow(file);
  const formats::Mesh& rm = restart.mesh;
  const auto& fm = lm.file_mesh;
  if (rm.node_count() != fm.node_count() || rm.triangles != fm.triangles || rm.quads != fm.quads) {
    restart.fail("/mesh", "restart mesh has a different topology (" +
                              std::to_string(rm.node_count()) + " nodes, " +
                              std::to_string(rm.cell_count()) + " cells) than the flow mesh (" +
                              std::to_string(fm.node_count()) + " nodes, " +
                              std::to_string(fm.cell_count()) + " cells)");
  }
  return restart;
}

std::vector<State> primitive_states(const formats::Flow& flow) {
  std::vector<State> w(flow.density.size());
  for (std::size_t k = 0; k < w.size(); ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    w[k] = {flow.density[k], flow.velocity(row, 0), flow.velocity(row, 1), flow.pressure[k]};
  }
  return w;
}

// One run of the stage, in named phases: the options checked and the mesh loaded, the boundary
// conditions mapped from the mesh's boundary kinds, the solver set up and started (uniform,
// internal-flow or restart state), the solve (steady, with a first-order start, or
// time-accurate), the integrals (mass flow, thrust, discharge coefficient), the wall traces and
// the heat-transfer probe, and flow.h5.
class FlowStage {
 public:
  FlowStage(const RunOptions& options, const Logger& logger)
      : o(options),
        log(logger),
        lm((check_options(options), load_mesh(options.mesh_file))),
        sst_model(o.model == "sst" || o.model == "sst-v"),
        turbulent(o.model == "sa" || o.model == "sa-noft2" || sst_model),
        viscous(o.model == "laminar" || turbulent),
        gas{o.gamma, o.gas_constant},
        t_inf(o.ambient_temperature),
        w_inf{o.ambient_pressure / (o.gas_constant * t_inf),
              o.freestream_mach * std::sqrt(o.gamma * o.gas_constant * t_inf), 0.0,
              o.ambient_pressure} {}

  RunResult run() {
    from_restart = o.restart_file.has_value();
    map_boundaries();
    configure();
    start();
    solve();
    integrate();
    take_wall_traces();
    probe_heat_transfer();
    write();
    return result;
  }

 private:
  static void check_options(const RunOptions& o) {
    require(o.gamma > 1.0 && o.gamma < 2.0,
            "--gamma must lie in (1, 2), got " + text::format_number(o.gamma));
    require(o.gas_constant > 0.0, "--gas-constant must be positive");
    require(o.ambient_pressure > 0.0, "--ambient-pressure must be positive");
    require(o.model == "euler" || o.model == "laminar" || o.model == "sa" ||
                o.model == "sa-noft2" || o.model == "sst" || o.model == "sst-v",
            "--model must be euler, laminar, sa, sa-noft2, sst or sst-v, got '" + o.model + "'");
    require(
        o.roe_jacobian == "exact-first-order" || o.roe_jacobian == "exact" ||
            o.roe_jacobian == "frozen",
        "--roe-jacobian must be exact-first-order, exact or frozen, got '" + o.roe_jacobian + "'");
    require(o.farfield_flux == "roe" || o.farfield_flux == "riemann",
            "--farfield-flux must be roe or riemann, got '" + o.farfield_flux + "'");
  }

  // The boundary condition of each mesh boundary from its kind, and which curves are inflow,
  // outflow and walls (for the integrals and the traces).
  void map_boundaries() {
    for (std::size_t b = 0; b < lm.kinds.size(); ++b) {
      const std::string& kind = lm.kinds[b];
      const std::string where =
          o.mesh_file.string() + ": /mesh/boundaries/" + lm.mesh.boundaries[b].name;
      BoundaryCondition bc;
      if (kind == "inflow") {
        require(o.stagnation_pressure > 0.0 && o.stagnation_temperature > 0.0,
                where + ": an inflow boundary needs --p0 and --T0");
        require(o.stagnation_pressure >= o.ambient_pressure,
                "nozzle pressure ratio p0/p_ambient = " +
                    text::format_number(o.stagnation_pressure / o.ambient_pressure) +
                    " is below 1; raise --p0 or lower --ambient-pressure");
        bc.kind = BcKind::stagnation_inflow;
        bc.total_pressure = o.stagnation_pressure;
        bc.total_temperature = o.stagnation_temperature;
        bc.flow_angle = o.inflow_angle * std::acos(-1.0) / 180.0;
        has_inflow = true;
        inflow_curves.push_back(static_cast<int>(b));
      } else if (kind == "farfield") {
        bc.kind = BcKind::farfield;
        bc.freestream = w_inf;
        bc.riemann_invariants = o.farfield_flux == "riemann";
        has_farfield = true;
      } else if (kind == "outflow") {
        bc.kind = BcKind::pressure_outflow;
        bc.static_pressure = o.ambient_pressure;
        outflow_curves.push_back(static_cast<int>(b));
      } else if (kind == "wall") {
        nozzle_wall_curves.push_back(static_cast<int>(b));
        if (viscous) {
          bc.kind = o.wall_temperature ? BcKind::wall_isothermal : BcKind::wall_adiabatic;
          if (o.wall_temperature)
            bc.wall_temperature = *o.wall_temperature;
        } else {
          bc.kind = BcKind::slip_wall;
        }
        wall_curves.push_back(static_cast<int>(b));
      } else if (kind == "slip_wall") {
        bc.kind = BcKind::slip_wall;
        wall_curves.push_back(static_cast<int>(b));
      } else if (kind == "symmetry" || kind == "axis") {
        bc.kind = BcKind::symmetry;
      } else {
        throw BadInput(where + ": unknown boundary kind '" + kind + "'");
      }
      bcs.push_back(bc);
    }
  }

  // Solver settings from the options and the boundaries (reference state, inflow ramp), and the
  // restart file if any.
  void configure() {
    settings = o.settings;
    settings.renumber = o.renumber;
    settings.renumber_lines = o.node_ordering == "lines";
    settings.viscous = viscous;
    settings.turbulent = turbulent;
    settings.sa_ft2 = o.model != "sa-noft2";
    settings.turbulence_model =
        sst_model ? TurbulenceModel::sst : TurbulenceModel::spalart_allmaras;
    settings.sst_variant = o.model == "sst-v" ? sst::Variant::sst_v : sst::Variant::sst2003;
    settings.sa_exact_jacobian = o.turbulence_jacobian == "exact";
    settings.roe_jacobian = o.exact_jacobian || o.roe_jacobian == "exact" ? RoeJacobian::exact
                            : o.roe_jacobian == "frozen"                  ? RoeJacobian::frozen
                                                         : RoeJacobian::exact_first_order;
    settings.matrix_free = o.matrix_free == "true"   ? MatrixFree::on
                           : o.matrix_free == "auto" ? MatrixFree::after_limiter_freeze
                                                     : MatrixFree::off;
    settings.turbulence_coupling = o.turbulence_coupling == "coupled" ? TurbulenceCoupling::coupled
                                   : o.turbulence_coupling == "auto"
                                       ? TurbulenceCoupling::automatic
                                       : TurbulenceCoupling::segregated;
    settings.limit_turbulence_alone = o.turbulence_step_limit == "nu-tilde";
    settings.multigrid_post_smoother = o.multigrid_post_smoother == "jacobi"
                                           ? AggregationMultigrid::PostSmoother::jacobi
                                           : AggregationMultigrid::PostSmoother::ilu;
    if (sst_model && settings.turbulence_coupling != TurbulenceCoupling::segregated) {
      // a case's options may be written for SA; the same case run under SST keeps them
      log.info("--turbulence-coupling " + o.turbulence_coupling +
               " applies to Spalart-Allmaras; k-omega SST solves k and omega segregated");
      settings.turbulence_coupling = TurbulenceCoupling::segregated;
    }
    p_ref = has_inflow ? o.stagnation_pressure : o.ambient_pressure;
    const double t_ref = has_inflow ? o.stagnation_temperature : t_inf;
    const double rho_ref = p_ref / (o.gas_constant * t_ref);
    const double c_ref = std::sqrt(o.gamma * o.gas_constant * t_ref);
    settings.reference_state = {rho_ref, c_ref, c_ref, p_ref};

    if (from_restart)
      restart = read_restart(*o.restart_file, lm);
    if (restart && settings.residual_reference <= 0.0 && restart->convergence.residual_reference) {
      // continue the residual drop of the run being restarted
      settings.residual_reference = *restart->convergence.residual_reference;
    }
    // The ramp opens from the total pressure of the start state, the free stream's (isentropic
    // from the ambient state at --freestream-mach): air at rest gives the ambient pressure.
    const double m2 = o.freestream_mach * o.freestream_mach;
    const double freestream_total_pressure =
        o.ambient_pressure * std::pow(1.0 + 0.5 * (o.gamma - 1.0) * m2, o.gamma / (o.gamma - 1.0));
    if (has_inflow && !from_restart) {
      // A jet started from the free stream: open the valve over the first iterations (see
      // SolverSettings::inflow_ramp_iterations) when there is something to open, i.e. the inflow
      // total pressure is above the free stream's (by more than 0.1 %: the TMR plate's p0 is the
      // free stream's own, and ramping from the ambient static pressure there made a transient
      // of its own and held the first-order start to iteration 51). Internal flows start from
      // moving gas instead.
      const bool driven = o.stagnation_pressure > 1.001 * freestream_total_pressure;
      settings.inflow_ramp_iterations =
          o.inflow_ramp >= 0 ? o.inflow_ramp : (has_farfield && driven ? 50 : 0);
      settings.inflow_ramp_start_pressure = freestream_total_pressure;
    } else if (o.inflow_ramp > 0) {
      settings.inflow_ramp_iterations = o.inflow_ramp;
      settings.inflow_ramp_start_pressure = freestream_total_pressure;
    }
  }

  // The solver and its start state.
  void start() {
    // Each steady solve's progress (iterations against the limit, rate, time left) on stderr.
    settings.on_iteration = [this](int iteration) {
      if (progress_)
        progress_->update(static_cast<std::size_t>(iteration));
    };
    solver_ = std::make_unique<FlowSolver>(lm.mesh, lm.geometry, gas, bcs, settings);
    FlowSolver& solver = *solver_;
    if (settings.renumber_lines) {
      log.info("node ordering: " + std::to_string(solver.ordering_lines()) +
               " lines of strongly coupled nodes (" + std::to_string(solver.ordering_line_nodes()) +
               " of " + std::to_string(solver.dual().num_nodes) + " nodes) kept contiguous");
    }
    if (from_restart) {
      solver.set_primitive(primitive_states(*restart));
      if (sst_model) {
        if (!restart->turbulent_kinetic_energy.empty() &&
            !restart->specific_dissipation_rate.empty()) {
          solver.set_sst(restart->turbulent_kinetic_energy, restart->specific_dissipation_rate);
        } else {
          log.info(
              "restart file has no /fields/point/turbulent_kinetic_energy and "
              "specific_dissipation_rate (not an SST run): k and omega start from their "
              "free-stream values, the mean flow from the restart");
        }
      } else if (turbulent) {
        if (!restart->nu_tilde.empty()) {
          solver.set_nu_tilde(restart->nu_tilde);
        } else {
          log.info(
              "restart file has no /fields/point/nu_tilde: Spalart-Allmaras starts from the "
              "free-stream value");
        }
      }
      log.info("restart from " + o.restart_file->string());
      // Why freeze: a converged second-order state reached its last iterations with the limiter
      // frozen; evaluated afresh every iteration on a restart, the Venkatakrishnan limiter chatters
      // at the shocks and the separation again and the restart climbs back to the limit-cycle
      // level first (config2 with a pinned hinge, fifth coupling iterate, 56k nodes: residual
      // 6.5e2 at the restart, 1.1e4 ten iterations later; three Newton phases failed, not
      // converged in 2000 iterations; held: converged in 60). A Newton phase that fails still
      // falls back to the live limiter (FlowSolver::solve).
      if (settings.order >= 2 && settings.limiter && o.time.time_step <= 0.0 &&
          o.restart_limiter == "frozen") {
        solver.hold_limiter(true);
        log.info("restart: limiter held at the restart state's values");
      }
    } else if (const auto q = quasi_one_dimensional_state()) {
      solver.set_primitive(q->states);
      log.info("quasi-1D start: " + q->summary());
    } else if (has_farfield || !has_inflow) {
      solver.set_uniform(w_inf);
    } else {
      // internal flow: start at Mach 0.2 from the inflow total conditions, along the inflow angle
      const double m0 = 0.2;
      const double t = o.stagnation_temperature / (1.0 + 0.5 * (o.gamma - 1.0) * m0 * m0);
      const double p =
          o.stagnation_pressure * std::pow(t / o.stagnation_temperature, o.gamma / (o.gamma - 1.0));
      const double a = o.inflow_angle * std::acos(-1.0) / 180.0;
      const double u = m0 * std::sqrt(o.gamma * o.gas_constant * t);
      solver.set_uniform({p / (o.gas_constant * t), u * std::cos(a), u * std::sin(a), p});
    }
    log.info("mesh " + o.mesh_file.string() + ": " + std::to_string(lm.mesh.num_points()) +
             " nodes, " + std::to_string(lm.mesh.triangles.size()) + " triangles, " +
             std::to_string(lm.mesh.quads.size()) + " quads; " + o.model +
             (lm.geometry == Geometry::axisymmetric ? ", axisymmetric" : ", planar"));
  }

  // --initial-state: the quasi-1D start is for a duct from an inflow at its smallest x to an
  // outflow at its largest, with no far field (a jet's plume is no duct); auto takes it where that
  // holds, quasi-1d insists.
  bool quasi_one_dimensional_applies() const {
    if (o.initial_state == "uniform")
      return false;
    auto mean_x = [&](const std::vector<int>& curves) {
      double sum = 0.0;
      int count = 0;
      for (int c : curves)
        for (const auto& e : lm.mesh.boundaries[static_cast<std::size_t>(c)].edges) {
          sum += lm.mesh.points[static_cast<std::size_t>(e[0])].x;
          ++count;
        }
      return count > 0 ? sum / count : 0.0;
    };
    std::string why;
    if (!has_inflow)
      why = "the mesh has no inflow boundary";
    else if (has_farfield)
      why = "the mesh has a far field";
    else if (outflow_curves.empty())
      why = "the mesh has no outflow boundary";
    else if (!(mean_x(inflow_curves) < mean_x(outflow_curves)))
      why = "the inflow boundary does not lie upstream (at smaller x) of the outflow";
    else if (!(o.stagnation_pressure > o.ambient_pressure))
      why = "the outflow pressure is not below the inflow total pressure";
    if (why.empty())
      return true;
    if (o.initial_state == "quasi-1d")
      throw UsageError("--initial-state quasi-1d needs a duct from an inflow to an outflow: " +
                       why);
    return false;
  }

  // The quasi-1D start state where it applies; a duct whose sections it cannot take (a station
  // with no fluid: the mesh has a gap along x) is refused with --initial-state quasi-1d and
  // starts uniform with auto.
  std::optional<Quasi1dStart> quasi_one_dimensional_state() const {
    if (!quasi_one_dimensional_applies())
      return std::nullopt;
    try {
      return quasi_one_dimensional_start(lm.mesh, lm.geometry, gas, o.stagnation_pressure,
                                         o.stagnation_temperature, o.ambient_pressure);
    } catch (const std::invalid_argument& e) {
      if (o.initial_state == "quasi-1d")
        throw UsageError(std::string("--initial-state quasi-1d: ") + e.what());
      log.info(std::string("no quasi-1D start (") + e.what() + "): uniform start");
      return std::nullopt;
    }
  }

  // The solve: time-accurate (dual time stepping, flow.h5 then holds the time averages),
  // second order after a first-order start, or one steady solve.
  void solve() {
    if (o.time.time_step > 0.0) {
      solve_time_accurate();
    } else if (o.first_order_start && settings.order >= 2 && !from_restart) {
      solve_with_first_order_start();
    } else {
      result.report = solve_showing_progress(*solver_, "steady solve", settings.max_iterations);
      if (from_restart && !result.report.converged && o.restart_fallback)
        solve_again_from_the_start_state();
    }
  }

  // A restart that did not converge, solved again as if there were no restart file: from the
  // uniform or internal-flow start state, with the first-order start if it is on. Why: a coupling
  // iterate whose walls moved far from the state it restarts from can be out of reach of that
  // state (config2's dynamic exchange with the sliding mount: between exchanges 4 and 5 the
  // trailing edge swung 268 mm, and the restart diverged, its CFL number collapsing after 1,189
  // iterations; that geometry did not settle from the start state either, README "Restart").
  // The report is the second solve's; the log says what the first did.
  void solve_again_from_the_start_state() {
    const SolveReport failed = result.report;
    log.warn("the restart from " + o.restart_file->string() + " did not converge in " +
             std::to_string(failed.iterations) + " iterations (" + failed.stop_reason +
             "); solving again from the start state");
    from_restart = false;
    restart.reset();
    configure();
    start();
    solve();
  }

  // solver.solve() with a progress line for it; a solve stops at its iteration limit at the
  // latest, so the time left shown is an upper bound.
  SolveReport solve_showing_progress(FlowSolver& solver, const std::string& label,
                                     int max_iterations) {
    Progress progress(log, label, static_cast<std::size_t>(std::max(max_iterations, 0)),
                      {.unit = "iterations", .total_is_limit = true});
    progress_ = &progress;
    struct Reset {
      Progress*& current;
      ~Reset() { current = nullptr; }
    } reset{progress_};
    return solver.solve();
  }

  // Time-accurate run: the physical steps and their averages, a report of one row per physical
  // step, and the time-mean state left in the solver for the integrals, the eddy viscosity and
  // the heat-transfer probe.
  void solve_time_accurate() {
    FlowSolver& solver = *solver_;
    TimeAccurateSettings time = o.time;
    if (time.time_steps < 1 || time.statistics_start > time.time_steps) {
      throw BadInput("--time-step needs --time-steps >= 1 and --statistics-start (" +
                     std::to_string(time.statistics_start) + ") <= --time-steps (" +
                     std::to_string(time.time_steps) + ")");
    }
    time.reference_pressure = p_ref;
    time.inner_limiter =
        o.inner_limiter == "predicted" ? InnerLimiter::predicted : InnerLimiter::live;
    time.print_every = settings.print_every;
    time.cfl_start = settings.cfl_start;
    time.cfl_max = settings.cfl_max;
    result.time_average = run_time_accurate(solver, time, wall_curves);
    const TimeAccurateResult& ta = *result.time_average;
    log.info("time-accurate: " + std::to_string(time.time_steps) + " steps of " +
             text::format_number(time.time_step) + " s (" + std::to_string(ta.iterations) +
             " inner iterations, " + std::to_string(ta.unconverged_steps) +
             " steps short of the inner drop); mean over " + std::to_string(ta.averaged_steps) +
             " steps, wall pressure means of the window's halves differ by " +
             text::format_number(ta.mean_change) + " p0");
    // the report of a time-accurate run: one row per physical step
    SolveReport& r = result.report;
    r.converged = ta.mean_converged;
    r.iterations = static_cast<int>(ta.iterations);
    r.linear_iterations = ta.linear_iterations;
    r.residual_evaluations = ta.residual_evaluations;
    r.residual_seconds = ta.residual_seconds;
    r.wall_time = ta.wall_time;
    for (std::size_t k = 0; k < ta.history.size(); ++k) {
      IterationRecord rec;
      rec.iteration = static_cast<int>(k) + 1;
      rec.residual = ta.history[k].residual;
      r.history.push_back(rec);
    }
    // integrals, eddy viscosity and the heat-transfer probe start from the time-mean state
    solver.set_primitive(ta.mean_primitive);
    if (turbulent) {
      solver.set_nu_tilde(ta.mean_nu_tilde);
      solver.set_sst(ta.mean_k, ta.mean_omega);
    }
  }

  // Second order without a restart: the first-order stage, then the second-order one from its
  // state, continuing its residual drop at full inflow pressure; one report of both.
  void solve_with_first_order_start() {
    FlowSolver& solver = *solver_;
    const SolveReport first = solve_first_order_stage();
    // the second stage continues the first one's residual drop and starts at full inflow pressure
    solver.set_residual_reference(first.residual_reference);
    solver.set_inflow_ramp(0);
    if (o.second_order_cfl_start)
      solver.set_cfl_start(*o.second_order_cfl_start);
    SolveReport second = solve_showing_progress(solver, "second order", settings.max_iterations);
    for (auto& rec : second.history) {
      rec.iteration += first.iterations;
      rec.wall_time += first.wall_time;
    }
    second.history.insert(second.history.begin(), first.history.begin(), first.history.end());
    second.iterations += first.iterations;
    second.linear_iterations += first.linear_iterations;
    second.residual_evaluations += first.residual_evaluations;
    second.residual_seconds += first.residual_seconds;
    second.backoffs += first.backoffs;
    second.steps_taken_back += first.steps_taken_back;
    second.steps_shortened += first.steps_shortened;
    second.step_halvings += first.step_halvings;
    second.wall_time += first.wall_time;
    result.report = std::move(second);
  }

  // The first-order start (first_order_start_settings) in a solver of its own, from the start
  // state; its final state (and nu_tilde) becomes the second-order solver's.
  SolveReport solve_first_order_stage() {
    FlowSolver& solver = *solver_;
    const SolverSettings first_settings =
        first_order_start_settings(settings, o.first_order_start_drop);
    FlowSolver first_solver(lm.mesh, lm.geometry, gas, bcs, first_settings);
    first_solver.set_primitive(solver.primitive());
    SolveReport first =
        solve_showing_progress(first_solver, "first-order start", first_settings.max_iterations);
    log.info(std::string("first-order start: ") +
             (first.converged ? "converged" : "NOT converged") + " in " +
             std::to_string(first.iterations) + " iterations, residual drop " +
             text::format_number(first.residual_drop) + "; continuing at second order");
    solver.set_primitive(first_solver.primitive());
    if (turbulent) {
      solver.set_nu_tilde(first_solver.nu_tilde());
      solver.set_sst(first_solver.sst_k(), first_solver.sst_omega());
    }
    return first;
  }

  void integrate() {
    FlowSolver& solver = *solver_;
    // Integrals. With outflow boundaries: mass flow and gross thrust through them,
    // T = sum (rho u (u.n) + (p - p_amb) n) dS (Sutton and Biblarz 2017, eq. 2-14). Without (a
    // nozzle discharging into a far-field plume region): the same thrust from the momentum
    // balance of the internal flow, T = -sum over inflow and `wall` curves of
    // (rho u (u.n) + (p - p_amb) n) dS, and the mass flow entering through the inflow.
    const double scale = lm.geometry == Geometry::axisymmetric ? 2.0 * std::acos(-1.0) : 1.0;
    auto momentum_minus_ambient = [&](int b) {
      const BoundaryIntegral bi = solver.boundary_integral(b);
      Vec2 f = bi.force;
      for (const auto& face : solver.dual().boundary_faces) {
        if (face.curve == b)
          f = f - o.ambient_pressure * face.normal;
      }
      return std::pair<double, Vec2>{bi.mass_flow, f};
    };
    if (!outflow_curves.empty()) {
      for (int b : outflow_curves) {
        const auto [m, f] = momentum_minus_ambient(b);
        result.mass_flow += scale * m;
        result.thrust_x += scale * f.x;
        result.thrust_y += scale * f.y;
      }
    } else if (!inflow_curves.empty()) {
      for (int b : inflow_curves)
        result.mass_flow -= scale * momentum_minus_ambient(b).first;
      std::vector<int> control_surface = inflow_curves;
      control_surface.insert(control_surface.end(), nozzle_wall_curves.begin(),
                             nozzle_wall_curves.end());
      for (int b : control_surface) {
        const Vec2 f = momentum_minus_ambient(b).second;
        result.thrust_x -= scale * f.x;
        result.thrust_y -= scale * f.y;
      }
    }
    if (o.throat_area && has_inflow) {
      // ideal: isentropic with a sonic throat (the flow.md definition)
      const double ideal = choked_mass_flux(o.stagnation_pressure, o.stagnation_temperature,
                                            o.gamma, o.gas_constant) *
                           *o.throat_area;
      result.discharge_coefficient = result.mass_flow / ideal;
    }
  }

  void take_wall_traces() {
    FlowSolver& solver = *solver_;
    // Output in the numbering of the input mesh: fields and traces of the solution, before the
    // heat-transfer probe changes the state.
    w_solver = solver.primitive();
    if (result.time_average) {
      traces = result.time_average->mean_traces;
    } else {
      traces = solver.wall_traces(wall_curves);
    }
    nu_tilde = turbulent ? solver.nu_tilde() : std::vector<double>{};
    sst_k = solver.sst_k();
    sst_omega = solver.sst_omega();
    eddy_viscosity = turbulent ? solver.eddy_viscosity() : std::vector<double>{};
  }

  void probe_heat_transfer() {
    FlowSolver& solver = *solver_;
    const SolveReport& rep = result.report;
    // Heat transfer coefficient for tfmb-heat's convection condition: walls made isothermal
    // heat_transfer_dt below the adiabatic wall temperature, restarted from the adiabatic solution,
    // h = q_w / (T_aw - T_w) node by node (the adiabatic wall temperature is the recovery
    // temperature of the viscous solution).
    const double heat_transfer_dt = o.heat_transfer_dt;
    if (viscous && !o.wall_temperature && heat_transfer_dt > 0.0) {
      solver.make_walls_isothermal(heat_transfer_dt);
      // A 20 K change of a converged state. With the limiter evaluated afresh, the probe's state
      // differs from the adiabatic one by the limiter's change too, not by the wall temperature
      // alone (config1 at second-order SA, 52,717 nodes: h negative along the whole last flap, 187
      // iterations; restarted with a tighter criterion, its Newton phases failed at the lip
      // corners). Held at the converged state's values: h positive there, 78 iterations.
      solver.hold_limiter();
      solver.set_residual_reference(rep.residual_reference);
      // Converged as far as the solution it perturbs: the probe stops once its density residual is
      // down to the adiabatic solution's final level, or by the usual criteria. Realistic nozzle,
      // 52k nodes: 19 probe iterations instead of 77 (wall-pressure stationarity); h moves by 2-4 %
      // of its largest value on the flap walls (11 % on the nacelle, h ~ 50), and the flaps' beam
      // temperatures that tfmb-heat makes of it by at most 0.9 K (mean) and 0.12 K (through the
      // thickness), well inside what the emissivity's uncertainty moves them.
      solver.set_residual_drop(std::max(rep.residual_drop, settings.residual_drop));
      const SolveReport probe =
          solve_showing_progress(solver, "heat-transfer probe", settings.max_iterations);
      log.info("heat-transfer probe (walls " + text::format_number(heat_transfer_dt) +
               " K below adiabatic): " + (probe.converged ? "converged" : "NOT converged") +
               " in " + std::to_string(probe.iterations) + " iterations");
      const std::vector<WallTrace> probe_traces = solver.wall_traces(wall_curves);
      for (std::size_t c = 0; c < wall_curves.size(); ++c) {
        const WallTrace& probe_trace = probe_traces[c];
        // The wall heat flux of a trace is k dT/dn from the nodal gradient, a one-sided
        // difference over the first cell: it holds the gradient of the viscous heating there,
        // O(dy), not zero, even on the adiabatic wall (config1 SMOKE, NPR 5.423: -1e3..-4e4 W/m^2
        // against a 20 K response of 1.4e4..2.1e4, which made h negative on whole flaps). The
        // velocity field hardly changes in the probe, so the difference of the two evaluations is
        // the response to the wall temperature alone: h = (q_probe - q_adiabatic) / dT.
        const std::vector<double>& adiabatic = traces[c].heat_flux;
        std::vector<double> h(probe_trace.heat_flux.size());
        for (std::size_t k = 0; k < h.size(); ++k)
          h[k] = (probe_trace.heat_flux[k] - adiabatic[k]) / heat_transfer_dt;
        heat_transfer.push_back(std::move(h));
      }
    }
  }

  // flow.h5: the fields, the wall traces, the integrals, the convergence record and the
  // provenance; then the run's outcome in the log.
  void write() {
    formats::Flow out = output_fields();
    output_walls(out);
    output_integrals(out);
    output_convergence(out.convergence);
    formats::write_flow(o.output, out, provenance());
    log_outcome();
  }

  // The header, the mesh and the point fields of the solution (before the heat-transfer probe),
  // refused if any node's state is not physical.
  formats::Flow output_fields() const {
    const FlowSolver& solver = *solver_;
    const std::size_t n = lm.file_mesh.node_count();
    std::vector<double> rho(n), p(n), temp(n), mach(n);
    h5::MatrixXdR vel(n, 3);
    for (std::size_t k = 0; k < n; ++k) {
      const State& w = w_solver[k];
      rho[k] = w[0];
      p[k] = w[3];
      temp[k] = gas.temperature(w);
      mach[k] = std::hypot(w[1], w[2]) / gas.sound_speed(w);
      vel(k, 0) = w[1];
      vel(k, 1) = w[2];
      vel(k, 2) = 0.0;
      if (!(rho[k] > 0.0 && p[k] > 0.0 && std::isfinite(mach[k]) &&
            std::isfinite(vel(k, 0) + vel(k, 1)))) {
        // the solver only keeps physical states; never hand a non-physical field to the next stage
        throw InternalError(o.output.string() + ": node " + std::to_string(k) +
                            " has a non-physical final state (rho " + text::format_number(rho[k]) +
                            ", p " + text::format_number(p[k]) + "); nothing written");
      }
    }
    formats::Flow out;
    out.header.creator = "tfmb-flow " + cli::version();
    out.header.geometry = lm.geometry == Geometry::axisymmetric ? "axisymmetric" : "planar";
    out.header.depth = lm.depth;
    out.mesh = lm.file_mesh;
    out.density = rho;
    out.velocity = vel;
    out.pressure = p;
    out.temperature = temp;
    out.mach = mach;
    if (turbulent) {
      out.nu_tilde = nu_tilde;
      out.turbulent_kinetic_energy = sst_k;
      out.specific_dissipation_rate = sst_omega;
      out.eddy_viscosity = eddy_viscosity;
      out.wall_distance = solver.wall_distance();
    }
    return out;
  }

  // One /walls entry per wall curve: its trace, the time-accurate run's pressure RMS and the
  // heat-transfer probe's results.
  void output_walls(formats::Flow& out) const {
    for (std::size_t c = 0; c < wall_curves.size(); ++c) {
      const WallTrace& t = traces[c];
      formats::FlowWall wall;
      wall.name = lm.mesh.boundaries[wall_curves[c]].name;
      wall.node.assign(t.node.begin(), t.node.end());
      wall.s = t.s;
      wall.x = t.x;
      wall.y = t.y;
      wall.pressure = t.pressure;
      wall.temperature = t.temperature;
      wall.wall_shear = t.shear_stress;
      wall.heat_flux = t.heat_flux;
      for (const Vec2& normal : t.normal)
        wall.normal.emplace_back(normal.x, normal.y);
      if (result.time_average)
        wall.pressure_rms = result.time_average->pressure_rms[c];
      if (!heat_transfer.empty()) {
        wall.adiabatic_wall_temperature = t.temperature;
        wall.heat_transfer_coefficient = heat_transfer[c];
      }
      out.walls.push_back(std::move(wall));
    }
  }

  // The integrals and the conditions of the run.
  void output_integrals(formats::Flow& out) const {
    out.mass_flow = result.mass_flow;
    out.thrust_x = result.thrust_x;
    out.thrust_y = result.thrust_y;
    out.thrust_angle = std::atan2(result.thrust_y, result.thrust_x) * 180.0 / std::acos(-1.0);
    out.discharge_coefficient = result.discharge_coefficient;
    out.stagnation_pressure = o.stagnation_pressure;
    out.stagnation_temperature = o.stagnation_temperature;
    out.ambient_pressure = o.ambient_pressure;
    out.gamma = o.gamma;
    out.gas_constant = o.gas_constant;
  }

  // What the convergence criterion was (and which part was met), in words for
  // /convergence@criterion.
  std::string convergence_criterion() const {
    const SolveReport& rep = result.report;
    std::string criterion = "density residual (RMS of residual/volume) below " +
                            text::format_number(settings.residual_drop) + " of its largest value";
    if (settings.stationary_tolerance > 0.0) {
      criterion +=
          ", or wall pressure (relative to " + text::format_number(settings.reference_state[3]) +
          " Pa) and wall pressure force changing by less than " +
          text::format_number(settings.stationary_tolerance) + " per iteration for " +
          std::to_string(settings.stationary_iterations) + " iterations" +
          (rep.converged
               ? (rep.converged_by_stationarity ? " (met: stationarity)" : " (met: residual)")
               : "");
    }
    if (result.time_average) {
      criterion = "time average over steps " + std::to_string(o.time.statistics_start) + ".." +
                  std::to_string(o.time.time_steps) +
                  ": wall pressure means of the window's two halves within " +
                  text::format_number(o.time.statistics_tolerance) + " of " +
                  text::format_number(settings.reference_state[3]) + " Pa";
    }
    return criterion;
  }

  // /convergence: the outcome and its counts, where an unconverged run stopped, the
  // time-accurate run's window and history, and the residual history.
  void output_convergence(formats::FlowConvergence& convergence) const {
    const SolveReport& rep = result.report;
    convergence.converged = rep.converged;
    convergence.criterion = convergence_criterion();
    convergence.iterations = rep.iterations;
    convergence.residual_reference = rep.residual_reference;
    convergence.linear_iterations = rep.linear_iterations;
    convergence.residual_evaluations = rep.residual_evaluations;
    convergence.residual_seconds = rep.residual_seconds;
    convergence.wall_time = rep.wall_time;
    if (!rep.converged && !rep.stop_reason.empty()) {
      convergence.stop_reason = rep.stop_reason;
      convergence.worst_residual_x = rep.worst_residual_at.x;
      convergence.worst_residual_y = rep.worst_residual_at.y;
      convergence.least_relaxation = rep.least_relaxation;
      convergence.least_relaxed_x = rep.least_relaxed_at.x;
      convergence.least_relaxed_y = rep.least_relaxed_at.y;
    }
    if (result.time_average) {
      const TimeAccurateResult& ta = *result.time_average;
      convergence.time_average = true;
      convergence.time_step = o.time.time_step;
      convergence.time_steps = o.time.time_steps;
      convergence.statistics_start = o.time.statistics_start;
      convergence.averaged_steps = ta.averaged_steps;
      convergence.mean_change = ta.mean_change;
      convergence.time_history.resize(static_cast<Eigen::Index>(ta.history.size()), 5);
      for (std::size_t k = 0; k < ta.history.size(); ++k) {
        const auto& rec = ta.history[k];
        convergence.time_history.row(static_cast<Eigen::Index>(k)) << rec.time,
            static_cast<double>(rec.inner_iterations), rec.inner_residual_drop, rec.wall_force.x,
            rec.wall_force.y;
      }
    }
    // Each equation's residual relative to its largest value in the run, the measure the
    // convergence criterion uses for the density: a jet started from air at rest has no density
    // residual at all in its first iteration, so the first value is no reference.
    std::vector<double> history;
    const std::array<double, 5> largest = largest_residuals(rep.history);
    for (const auto& rec : rep.history) {
      for (int v = 0; v < 4; ++v)
        history.push_back(largest[v] > 0.0 ? rec.residual[v] / largest[v] : 0.0);
    }
    convergence.residual_history = Eigen::Map<const h5::MatrixXdR>(
        history.data(), static_cast<Eigen::Index>(rep.history.size()), 4);
  }

  // /provenance: the command line, the options, and the input files.
  formats::Provenance provenance() const {
    formats::Provenance prov;
    prov.command_line = o.command_line;
    // Every option as given (declared once in main.cpp), then what the run resolved from them.
    prov.settings = o.settings_toml + "\n[resolved]\norder = " + std::to_string(settings.order) +
                    "\ncfl_max = " + cli::toml_float(settings.cfl_max) +
                    "\nlimiter = " + (settings.limiter ? "true" : "false") +
                    "\nthreads = " + std::to_string(settings.threads) + "\n";
    prov.inputs = {o.mesh_file};
    if (o.restart_file)
      prov.inputs.push_back(*o.restart_file);
    return prov;
  }

  // The run's outcome in the log: why and where an unconverged run stopped, and the summary
  // line (iterations, residual drop, mass flow, thrust, time).
  void log_outcome() const {
    const SolveReport& rep = result.report;
    if (!rep.converged && !rep.stop_reason.empty()) {
      log.warn("not converged: " + rep.stop_reason + "; largest density residual at (" +
               text::format_number(rep.worst_residual_at.x) + ", " +
               text::format_number(rep.worst_residual_at.y) + ") m; " +
               equation_drops_text(rep, settings.turbulent, settings.turbulence_model) + "; " +
               (rep.least_relaxation < 1.0
                    ? "last update relaxed to " + text::format_number(rep.least_relaxation) +
                          " at (" + text::format_number(rep.least_relaxed_at.x) + ", " +
                          text::format_number(rep.least_relaxed_at.y) + ") m"
                    : std::string("last update not relaxed")) +
               "; the last physical state is written");
    }
    // per unit depth (planar) or for the whole axisymmetric nozzle
    const bool whole = lm.geometry == Geometry::axisymmetric;
    const std::string how =
        result.time_average
            ? "time average over " + std::to_string(result.time_average->averaged_steps) +
                  " steps " + (rep.converged ? "converged" : "NOT converged") +
                  " (halves differ by " + text::format_number(result.time_average->mean_change) +
                  " p0), " + std::to_string(rep.iterations) + " inner iterations"
            : std::string(rep.converged ? "converged" : "NOT converged") + " in " +
                  std::to_string(rep.iterations) + " iterations";
    log.summary("wrote " + o.output.string() + ": " + how + " (" +
                std::to_string(rep.linear_iterations) + " linear), residual drop " +
                text::format_number(rep.residual_drop) + ", mass flow " +
                text::format_number(result.mass_flow) + (whole ? " kg/s" : " kg/(s m)") +
                ", thrust " + text::format_number(result.thrust_x) + (whole ? " N" : " N/m") +
                ", " + text::format_number(rep.wall_time) + " s");
  }

  const RunOptions& o;
  const Logger& log;
  LoadedMesh lm;
  const bool sst_model, turbulent, viscous;
  const PerfectGas gas;
  const double t_inf;
  const State w_inf;
  std::vector<BoundaryCondition> bcs;
  bool has_inflow = false, has_farfield = false;
  std::vector<int> outflow_curves, wall_curves, inflow_curves, nozzle_wall_curves;
  SolverSettings settings;
  double p_ref = 0.0;
  std::optional<formats::Flow> restart;
  bool from_restart = false;  // the solve starts from the restart file's state
  std::unique_ptr<FlowSolver> solver_;
  Progress* progress_ = nullptr;  // of the solve under way, if any
  RunResult result;
  std::vector<State> w_solver;  // the solution, before the heat-transfer probe changes it
  std::vector<WallTrace> traces;
  std::vector<double> nu_tilde, eddy_viscosity, sst_k, sst_omega;
  std::vector<std::vector<double>> heat_transfer;  // per wall curve [W/(m^2 K)]
};

}  // namespace

RunResult run(const RunOptions& o, const Logger& log) {
  return FlowStage(o, log).run();
}

}  // namespace tfmb::flow
