// tfmb-flow end to end through run(): flowmesh.h5 written with the formats library, flow.h5
// read back; restart; bad inputs exit with BadInput (code 3).
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <set>
#include <sstream>

#include "nparc_case.hpp"
#include "tfmb-flow/run.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/formats/files.hpp"
#include "tfmb/formats/flow.hpp"

using namespace tfmb;
using namespace tfmb::flow;

namespace {

std::filesystem::path temp_dir() {
  const auto d =
      std::filesystem::temp_directory_path() / ("tfmb_flow_run_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d;
}

void write_flowmesh(const std::filesystem::path& file, const flow::Mesh& m,
                    bool drop_outlet = false, const std::string& outlet_kind = "outflow") {
  formats::Mesh fm;
  fm.points.resize(static_cast<Eigen::Index>(m.points.size()), 2);
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    fm.points(static_cast<Eigen::Index>(i), 0) = m.points[i].x;
    fm.points(static_cast<Eigen::Index>(i), 1) = m.points[i].y;
  }
  fm.triangles.resize(static_cast<Eigen::Index>(m.triangles.size()), 3);
  for (std::size_t c = 0; c < m.triangles.size(); ++c) {
    for (int k = 0; k < 3; ++k)
      fm.triangles(static_cast<Eigen::Index>(c), k) = m.triangles[c][k];
  }
  fm.quads.resize(static_cast<Eigen::Index>(m.quads.size()), 4);
  for (std::size_t c = 0; c < m.quads.size(); ++c) {
    for (int k = 0; k < 4; ++k)
      fm.quads(static_cast<Eigen::Index>(c), k) = m.quads[c][k];
  }
  const std::map<std::string, std::string> kinds = {
      {"symmetry", "symmetry"}, {"outlet", outlet_kind}, {"wall", "wall"}, {"inlet", "inflow"}};
  // The flowmesh spec has each boundary's edges with the domain on their left, as the
  // counter-clockwise cell beside an edge runs it; structured_mesh runs its top and left
  // boundaries the other way, so those are turned round (their order reversed too).
  std::set<std::pair<int, int>> cell_edges;
  auto add_cell = [&](const auto& cell) {
    for (std::size_t k = 0; k < cell.size(); ++k)
      cell_edges.insert({cell[k], cell[(k + 1) % cell.size()]});
  };
  for (const auto& t : m.triangles)
    add_cell(t);
  for (const auto& q : m.quads)
    add_cell(q);
  for (const auto& b : m.boundaries) {
    if (drop_outlet && b.name == "outlet")
      continue;
    formats::Boundary fb;
    fb.kind = kinds.at(b.name);
    const std::size_t n = b.edges.size();
    const bool turn = n > 0 && !cell_edges.count({b.edges[0][0], b.edges[0][1]});
    fb.edges.resize(static_cast<Eigen::Index>(n), 2);
    for (std::size_t e = 0; e < n; ++e) {
      const auto& edge = turn ? b.edges[n - 1 - e] : b.edges[e];
      fb.edges(static_cast<Eigen::Index>(e), 0) = turn ? edge[1] : edge[0];
      fb.edges(static_cast<Eigen::Index>(e), 1) = turn ? edge[0] : edge[1];
    }
    fm.boundaries[b.name] = fb;
  }
  h5::Writer w(file);
  formats::Header header;
  header.creator = "test";
  formats::write_header(w, "flowmesh", header);
  formats::write_mesh(w, fm);
  w.commit();
}

RunOptions nozzle_options(const std::filesystem::path& dir) {
  RunOptions o;
  o.mesh_file = dir / "flowmesh.h5";
  o.output = dir / "flow.h5";
  o.stagnation_pressure = nparc::kP0;
  o.stagnation_temperature = nparc::kT0;
  o.ambient_pressure = 0.75 * nparc::kP0;
  o.throat_area = 1.0 * nparc::kInch;
  o.settings.max_iterations = 400;
  o.settings.print_every = 0;
  return o;
}

}  // namespace

TEST(FlowRun, NozzleEndToEndAndRestart) {
  const auto dir = temp_dir();
  write_flowmesh(dir / "flowmesh.h5", nparc::make_mesh(61, 16));
  std::ostringstream log_text;
  const Logger log("tfmb-flow", Verbosity::normal, log_text);
  RunOptions o = nozzle_options(dir);
  const RunResult r = run(o, log);
  ASSERT_TRUE(r.report.converged);
  const double mdot_exact =
      Quasi1dNozzle(nparc::area_in, 0, 5, 10, 1.4, 0.75).mass_flow(nparc::kP0, nparc::kT0, 287.05) *
      nparc::kInch;
  EXPECT_NEAR(r.mass_flow, mdot_exact, 0.005 * mdot_exact);
  EXPECT_NEAR(r.discharge_coefficient, 1.0, 0.005);
  EXPECT_GT(r.thrust_x, 0.0);

  const h5::Reader f = formats::open_checked(o.output, "flow");  // validates against the schema
  EXPECT_EQ(f.attr_i64("/convergence", "converged"), 1);
  const auto p = f.read_vector("/fields/point/pressure", 61 * 16);
  const auto wall_x = f.read_vector("/walls/wall/x");
  EXPECT_EQ(wall_x.size(), 61u);
  // ordered along the boundary's edges: the upper wall runs with the domain on its left, in -x
  for (std::size_t k = 1; k < wall_x.size(); ++k)
    EXPECT_LT(wall_x[k], wall_x[k - 1]);
  EXPECT_TRUE(std::filesystem::exists(dir / "flow.xdmf"));

  // restart from the converged file: nothing left to do, same solution
  RunOptions again = o;
  again.restart_file = o.output;
  again.output = dir / "flow2.h5";
  const RunResult r2 = run(again, log);
  EXPECT_TRUE(r2.report.converged);
  EXPECT_LT(r2.report.iterations, r.report.iterations / 2);
  EXPECT_NEAR(r2.mass_flow, r.mass_flow, 1e-4 * r.mass_flow);
  std::filesystem::remove_all(dir);
}

TEST(FlowRun, RestartThatDoesNotConvergeIsSolvedAgainFromTheStartState) {
  // A restart continues the residual drop of the run it restarts (its /convergence reference).
  // Given a reference 1e-12 of the real one, the restart cannot reach the drop within its
  // iteration limit: with the fallback (default) the run is solved again from the start state
  // and converges to the first run's solution; without it, it stops unconverged.
  const auto dir = temp_dir();
  write_flowmesh(dir / "flowmesh.h5", nparc::make_mesh(61, 16));
  std::ostringstream log_text;
  const Logger log("tfmb-flow", Verbosity::normal, log_text);
  RunOptions o = nozzle_options(dir);
  const RunResult first = run(o, log);
  ASSERT_TRUE(first.report.converged);
  formats::Flow unreachable = formats::read_flow(o.output);
  ASSERT_TRUE(unreachable.convergence.residual_reference);
  *unreachable.convergence.residual_reference *= 1e-12;
  formats::write_flow(dir / "unreachable.h5", unreachable, {});

  RunOptions again = o;
  again.restart_file = dir / "unreachable.h5";
  again.settings.max_iterations = 30;
  again.output = dir / "without.h5";
  again.restart_fallback = false;
  const RunResult without = run(again, log);
  EXPECT_FALSE(without.report.converged);
  EXPECT_EQ(without.report.iterations, 30);

  again.settings.max_iterations = o.settings.max_iterations;
  again.output = dir / "with.h5";
  again.restart_fallback = true;
  log_text.str("");
  const RunResult with = run(again, log);
  EXPECT_TRUE(with.report.converged);
  EXPECT_NE(log_text.str().find("did not converge in 400 iterations"), std::string::npos)
      << log_text.str();
  EXPECT_NE(log_text.str().find("solving again from the start state"), std::string::npos);
  EXPECT_EQ(with.report.iterations, first.report.iterations) << "the first run's solve, again";
  EXPECT_NEAR(with.mass_flow, first.mass_flow, 1e-9 * first.mass_flow);
  std::filesystem::remove_all(dir);
}

TEST(FlowRun, RestartOnDeformedMeshOfSameTopology) {
  // two-way coupling: the wall moves a little, the mesh keeps its topology, the flow restarts
  const auto dir = temp_dir();
  write_flowmesh(dir / "flowmesh.h5", nparc::make_mesh(61, 16));
  std::ostringstream log_text;
  const Logger log("tfmb-flow", Verbosity::quiet, log_text);
  RunOptions o = nozzle_options(dir);
  const RunResult first = run(o, log);
  ASSERT_TRUE(first.report.converged);
  flow::Mesh deformed = nparc::make_mesh(61, 16);
  for (auto& p : deformed.points)
    p.y *= 1.0 + 0.01 * std::sin(3.14159 * p.x / (10.0 * nparc::kInch));
  write_flowmesh(dir / "deformed.h5", deformed);
  RunOptions again = o;
  again.mesh_file = dir / "deformed.h5";
  again.restart_file = o.output;
  again.output = dir / "deformed_flow.h5";
  const RunResult second = run(again, log);
  EXPECT_TRUE(second.report.converged);
  EXPECT_LT(second.report.iterations, first.report.iterations);
  // the throat height grows by 1 %, and so does the choked mass flow
  EXPECT_NEAR(second.mass_flow / first.mass_flow, 1.01, 0.003);
  // --restart-limiter frozen (what a coupling iterate passes): the limiter held at the restart
  // state's values, Newton-Krylov steps from the first iteration; live (the default), defect
  // correction first
  EXPECT_NE(second.report.newton_from, 1);
  again.restart_limiter = "frozen";
  again.output = dir / "deformed_flow_held.h5";
  const RunResult held = run(again, log);
  EXPECT_TRUE(held.report.converged);
  EXPECT_EQ(held.report.newton_from, 1);
  std::printf(
      "restart on the deformed mesh: limiter held %d iterations, live %d (from scratch %d)\n",
      held.report.iterations, second.report.iterations, first.report.iterations);
  EXPECT_LT(held.report.iterations, second.report.iterations);
  EXPECT_NEAR(held.mass_flow / second.mass_flow, 1.0, 1e-4);
  // a large change since the restart file (the throat 20 % higher): the held limiter is released
  // at the first iteration (--held-limiter-max-drop), and the run converges as a live one
  flow::Mesh opened = nparc::make_mesh(61, 16);
  for (auto& p : opened.points)
    p.y *= 1.0 + 0.2 * std::sin(3.14159 * p.x / (10.0 * nparc::kInch));
  write_flowmesh(dir / "opened.h5", opened);
  again.mesh_file = dir / "opened.h5";
  again.output = dir / "opened_flow.h5";
  const RunResult released = run(again, log);
  EXPECT_TRUE(released.report.converged);
  EXPECT_NE(released.report.newton_from, 1);
  EXPECT_NEAR(released.mass_flow / first.mass_flow, 1.2, 0.02);
  std::filesystem::remove_all(dir);
}

TEST(FlowRun, BadInputs) {
  const auto dir = temp_dir();
  std::ostringstream log_text;
  const Logger log("tfmb-flow", Verbosity::quiet, log_text);
  write_flowmesh(dir / "flowmesh.h5", nparc::make_mesh(21, 6));
  RunOptions o = nozzle_options(dir);
  o.settings.max_iterations = 2;
  // NPR below 1
  RunOptions low = o;
  low.ambient_pressure = 2.0 * o.stagnation_pressure;
  EXPECT_THROW(run(low, log), BadInput);
  // untagged boundary
  write_flowmesh(dir / "untagged.h5", nparc::make_mesh(21, 6), true);
  RunOptions untagged = o;
  untagged.mesh_file = dir / "untagged.h5";
  EXPECT_THROW(run(untagged, log), BadInput);
  // restart of another topology
  run(o, log);  // writes flow.h5 on the 21 x 6 mesh
  {
    // two iterations do not converge: the file says why and where, the log warns
    const h5::Reader f(o.output);
    EXPECT_EQ(f.attr_i64("/convergence", "converged"), 0);
    EXPECT_EQ(f.attr_string("/convergence", "stop_reason"), "iteration limit (2) reached");
    EXPECT_TRUE(f.has_attr("/convergence", "worst_residual_x"));
    const std::string text = log_text.str();
    EXPECT_NE(
        text.find("not converged: iteration limit (2) reached; largest density residual at ("),
        std::string::npos)
        << text;
    // ... which equation is furthest from converged: the log's figures are the last row of the
    // file's residual history, each equation against its largest
    const auto history = f.read_matrix("/convergence/residual_history");
    const std::string names[4] = {"density", "x-momentum", "y-momentum", "energy"};
    const std::size_t drops = text.find("residuals against their largest: ");
    ASSERT_NE(drops, std::string::npos) << text;
    int furthest = 0;
    for (int v = 0; v < 4; ++v) {
      const std::size_t at = text.find(names[v] + " ", drops);
      ASSERT_NE(at, std::string::npos) << names[v] << text;
      const double logged = std::stod(text.substr(at + names[v].size() + 1));
      const double last = history(history.rows() - 1, v);
      EXPECT_NEAR(logged, last, 5e-3 * last) << names[v];
      if (last > history(history.rows() - 1, furthest))
        furthest = v;
    }
    EXPECT_NE(text.find("furthest from converged: " + names[furthest] + ", largest at ("),
              std::string::npos)
        << text;
  }
  write_flowmesh(dir / "other.h5", nparc::make_mesh(22, 6));
  RunOptions other = o;
  other.mesh_file = dir / "other.h5";
  other.restart_file = o.output;
  other.output = dir / "other_flow.h5";
  EXPECT_THROW(run(other, log), BadInput);
  std::filesystem::remove_all(dir);
}

// --initial-state quasi-1d: the start state of the NPARC duct is the quasi-1D nozzle flow (its
// throat and normal shock in the log, where the exact solution puts them), the run converges
// to the same flow as from the uniform start, and a duct that ends in a far field is refused.
TEST(FlowRun, QuasiOneDimensionalStartOfADuct) {
  const auto dir = temp_dir();
  write_flowmesh(dir / "flowmesh.h5", nparc::make_mesh(61, 16));
  std::ostringstream log_text;
  const Logger log("tfmb-flow", Verbosity::normal, log_text);
  RunOptions uniform = nozzle_options(dir);
  uniform.output = dir / "uniform.h5";
  const RunResult from_rest = run(uniform, log);
  ASSERT_TRUE(from_rest.report.converged);
  EXPECT_EQ(log_text.str().find("quasi-1D start"), std::string::npos);

  RunOptions o = nozzle_options(dir);
  o.initial_state = "quasi-1d";
  const RunResult r = run(o, log);
  ASSERT_TRUE(r.report.converged);
  const std::string text = log_text.str();
  const auto at = text.find("quasi-1D start: choked at x = ");
  ASSERT_NE(at, std::string::npos) << text;
  const Quasi1dNozzle exact(nparc::area_in, 0, 5, 10, 1.4, 0.75);
  const auto shock_at = text.find("normal shock at x = ", at);
  ASSERT_NE(shock_at, std::string::npos) << text;
  const double shock_x = std::stod(text.substr(shock_at + 20));
  EXPECT_NEAR(shock_x, exact.shock_position() * nparc::kInch,
              0.1 * nparc::kInch);  // 61 nodes in 10 in
  EXPECT_NEAR(r.mass_flow, from_rest.mass_flow, 1e-4 * from_rest.mass_flow);
  EXPECT_NEAR(r.thrust_x, from_rest.thrust_x, 1e-4 * std::abs(from_rest.thrust_x));

  // a far field instead of the outflow: no duct to take sections of; auto falls back to uniform
  write_flowmesh(dir / "farfield.h5", nparc::make_mesh(61, 16), false, "farfield");
  RunOptions open = o;
  open.mesh_file = dir / "farfield.h5";
  open.output = dir / "open.h5";
  open.settings.max_iterations = 1;
  EXPECT_THROW(run(open, log), UsageError);
  EXPECT_FALSE(std::filesystem::exists(open.output));
  open.initial_state = "auto";
  log_text.str("");
  run(open, log);
  EXPECT_EQ(log_text.str().find("quasi-1D start"), std::string::npos);
  std::filesystem::remove_all(dir);
}

// The stationarity criterion (--stationary-tolerance): stops once every wall pressure and the
// wall pressure force stop moving, before the residual has dropped 8 orders, with wall
// pressures equal to the fully converged ones to about the tolerance.
TEST(FlowRun, WallPressureStationarityCriterion) {
  const auto dir = temp_dir();
  write_flowmesh(dir / "flowmesh.h5", nparc::make_mesh(61, 16));
  std::ostringstream log_text;
  const Logger log("tfmb-flow", Verbosity::normal, log_text);
  RunOptions full = nozzle_options(dir);
  const RunResult r_full = run(full, log);
  ASSERT_TRUE(r_full.report.converged);
  RunOptions early = nozzle_options(dir);
  early.output = dir / "flow-stationary.h5";
  early.settings.stationary_tolerance = 1e-6;
  const RunResult r_early = run(early, log);
  ASSERT_TRUE(r_early.report.converged);
  EXPECT_TRUE(r_early.report.converged_by_stationarity);
  EXPECT_LT(r_early.report.iterations, r_full.report.iterations);
  const h5::Reader a = formats::open_checked(full.output, "flow");
  const h5::Reader b = formats::open_checked(early.output, "flow");
  const auto pa = a.read_vector("/walls/wall/pressure");
  const auto pb = b.read_vector("/walls/wall/pressure");
  double worst = 0.0;
  for (std::size_t k = 0; k < pa.size(); ++k)
    worst = std::max(worst, std::abs(pa[k] - pb[k]) / nparc::kP0);
  std::printf("stationarity: %d iterations against %d; largest wall-pressure difference %.2e p0\n",
              r_early.report.iterations, r_full.report.iterations, worst);
  EXPECT_LT(worst, 1e-5);
  EXPECT_NE(b.attr_string("/convergence", "criterion").find("met: stationarity"),
            std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(FlowRun, FirstOrderStartThenSecondOrder) {
  // --order 2 --first-order-start: one call converges first order, then second order from it;
  // the history holds both stages and the result is the second-order one (the same as a
  // separate restart would give)
  const auto dir = temp_dir();
  write_flowmesh(dir / "flowmesh.h5", nparc::make_mesh(61, 16));
  std::ostringstream log_text;
  const Logger log("tfmb-flow", Verbosity::normal, log_text);
  RunOptions o = nozzle_options(dir);
  o.settings.order = 2;
  o.first_order_start = true;
  const RunResult r = run(o, log);
  ASSERT_TRUE(r.report.converged);
  EXPECT_NE(log_text.str().find("first-order start: converged"), std::string::npos);
  const h5::Reader f = formats::open_checked(o.output, "flow");
  const auto history = f.read_matrix("/convergence/residual_history");
  EXPECT_EQ(static_cast<std::size_t>(history.rows()), r.report.history.size());

  RunOptions first = nozzle_options(dir);
  first.settings.order = 1;
  first.output = dir / "first.h5";
  const RunResult r1 = run(first, log);
  ASSERT_TRUE(r1.report.converged);
  RunOptions second = nozzle_options(dir);
  second.settings.order = 2;
  second.restart_file = first.output;
  second.output = dir / "second.h5";
  const RunResult r2 = run(second, log);
  ASSERT_TRUE(r2.report.converged);
  EXPECT_GT(r.report.iterations, r1.report.iterations);
  EXPECT_NEAR(r.mass_flow, r2.mass_flow, 1e-4 * r2.mass_flow);
  EXPECT_NEAR(r.thrust_x, r2.thrust_x, 1e-4 * std::abs(r2.thrust_x));
  std::filesystem::remove_all(dir);
}

// --second-order-cfl-start: the second stage starts at its own CFL number, the first at
// --cfl-start, and the run converges to the same flow.
TEST(FlowRun, SecondOrderStageStartsAtItsOwnCflNumber) {
  const auto dir = temp_dir();
  write_flowmesh(dir / "flowmesh.h5", nparc::make_mesh(61, 16));
  struct Stages {
    RunResult result;
    double first_cfl = 0.0, second_cfl = 0.0;  // each stage's first CFL number
  };
  auto two_stages = [&](std::optional<double> second_cfl, const char* name) {
    std::ostringstream log_text;
    const Logger log("tfmb-flow", Verbosity::normal, log_text);
    RunOptions o = nozzle_options(dir);
    o.settings.order = 2;
    o.first_order_start = true;
    o.second_order_cfl_start = second_cfl;
    o.output = dir / name;
    Stages stages{run(o, log)};
    // the first stage's length, from its log line "first-order start: converged in N iterations"
    const std::string text = log_text.str();
    const std::size_t at = text.find("first-order start: converged in ");
    EXPECT_NE(at, std::string::npos);
    const auto first_iterations = static_cast<std::size_t>(
        std::stoi(text.substr(at + std::strlen("first-order start: converged in "))));
    const auto& history = stages.result.report.history;
    // a converged stage records its N steps and the residual evaluation that met the criterion
    EXPECT_LT(first_iterations + 1, history.size());
    stages.first_cfl = history.front().cfl;
    stages.second_cfl = history.at(first_iterations + 1).cfl;
    return stages;
  };
  const Stages plain = two_stages(std::nullopt, "plain.h5");
  const Stages own = two_stages(50.0, "own.h5");
  ASSERT_TRUE(plain.result.report.converged);
  ASSERT_TRUE(own.result.report.converged);
  const double cfl_start = SolverSettings{}.cfl_start;
  EXPECT_EQ(plain.first_cfl, cfl_start);
  EXPECT_EQ(plain.second_cfl, cfl_start);
  EXPECT_EQ(own.first_cfl, cfl_start);
  EXPECT_EQ(own.second_cfl, 50.0);
  EXPECT_NEAR(own.result.mass_flow, plain.result.mass_flow, 1e-4 * plain.result.mass_flow);
  EXPECT_NEAR(own.result.thrust_x, plain.result.thrust_x, 1e-4 * std::abs(plain.result.thrust_x));
  std::filesystem::remove_all(dir);
}

TEST(FlowRun, TimeAccurateRunOfASteadyFlowWritesItsMean) {
  // a converged steady nozzle flow continued time-accurately stays where it is: the mean is the
  // steady solution, the wall-pressure RMS vanishes, and flow.h5 records the time average
  const auto dir = temp_dir();
  write_flowmesh(dir / "flowmesh.h5", nparc::make_mesh(61, 16));
  std::ostringstream log_text;
  const Logger log("tfmb-flow", Verbosity::normal, log_text);
  RunOptions steady = nozzle_options(dir);
  steady.settings.residual_drop = 1e-10;
  ASSERT_TRUE(run(steady, log).report.converged);
  RunOptions o = nozzle_options(dir);
  o.restart_file = steady.output;
  o.output = dir / "flow-mean.h5";
  o.time.time_step = 1e-5;  // about 10 acoustic transit times of a cell
  o.time.time_steps = 8;
  o.time.statistics_start = 3;
  o.time.inner_residual_drop = 1e-6;
  const RunResult r = run(o, log);
  ASSERT_TRUE(r.time_average.has_value());
  EXPECT_TRUE(r.report.converged);
  EXPECT_EQ(r.time_average->averaged_steps, 6);
  EXPECT_LT(r.time_average->mean_change, 1e-6);
  const h5::Reader a = formats::open_checked(steady.output, "flow");
  const h5::Reader b = formats::open_checked(o.output, "flow");  // the 1.2 layout
  EXPECT_EQ(b.attr_i64("/convergence", "time_average"), 1);
  EXPECT_EQ(b.attr_i64("/convergence", "averaged_steps"), 6);
  EXPECT_EQ(b.read_matrix("/convergence/time_history").rows(), 8);
  EXPECT_EQ(b.read_matrix("/convergence/residual_history").rows(), 8);
  const auto pa = a.read_vector("/walls/wall/pressure");
  const auto pb = b.read_vector("/walls/wall/pressure");
  const auto rms = b.read_vector("/walls/wall/pressure_rms");
  ASSERT_EQ(pa.size(), pb.size());
  double worst = 0.0, worst_rms = 0.0;
  for (std::size_t k = 0; k < pa.size(); ++k) {
    worst = std::max(worst, std::abs(pa[k] - pb[k]) / nparc::kP0);
    worst_rms = std::max(worst_rms, rms[k] / nparc::kP0);
  }
  std::printf("time-accurate continuation of the steady nozzle: mean within %.2e p0 of the steady "
              "wall pressure, RMS %.2e p0\n",
              worst, worst_rms);
  EXPECT_LT(worst, 1e-8);
  EXPECT_LT(worst_rms, 1e-9);

  RunOptions bad = o;
  bad.time.statistics_start = 9;  // after the last step
  EXPECT_THROW(run(bad, log), BadInput);
  std::filesystem::remove_all(dir);
}

// The heat-transfer probe's h on a supersonic laminar wall: the NPARC nozzle at exit ratio 0.16
// (supersonic from the throat on) with a no-slip adiabatic wall, its cells clustered to the wall
// (exponentially, a first cell of about 1e-3 of the local height). The traced wall heat flux is
// a one-sided difference over the first cell and holds the gradient of the viscous heating there
// even on the adiabatic wall (here up to 5.5 kW/m^2 against a 20 K response of about 0.7);
// taken as the probe's response, it made h negative (-145). h is the difference
// of the probe's and the adiabatic run's evaluations, and must be positive along the whole wall
// (the probe's wall is colder than T_aw everywhere: by the maximum principle heat flows into it).
TEST(FlowRun, HeatTransferCoefficientIsPositiveOnASupersonicWall) {
  const auto dir = temp_dir();
  StructuredMeshSpec spec;
  spec.ni = 61;
  spec.nj = 41;
  spec.map = [](double xi, double eta) {
    const double x = 10.0 * xi;
    const double beta = 5.0;  // exponential clustering to the wall at eta = 1
    const double y = 1.0 - (std::exp(beta * (1.0 - eta)) - 1.0) / (std::exp(beta) - 1.0);
    return Vec2{x * nparc::kInch, y * nparc::area_in(x) * nparc::kInch};
  };
  spec.split = [](int i, int j) { return j < 20 && (i + j) % 3 == 0; };
  spec.bottom = "symmetry";
  spec.right = "outlet";
  spec.top = "wall";
  spec.left = "inlet";
  write_flowmesh(dir / "flowmesh.h5", structured_mesh(spec));
  std::ostringstream log_text;
  const Logger log("tfmb-flow", Verbosity::normal, log_text);
  RunOptions o = nozzle_options(dir);
  o.model = "laminar";
  o.ambient_pressure = 0.16 * nparc::kP0;
  o.settings.max_iterations = 600;
  const RunResult r = run(o, log);
  ASSERT_TRUE(r.report.converged) << log_text.str();
  const h5::Reader f = formats::open_checked(o.output, "flow");
  const auto x = f.read_vector("/walls/wall/x");
  const auto h = f.read_vector("/walls/wall/heat_transfer_coefficient");
  const auto q_adiabatic = f.read_vector("/walls/wall/heat_flux");
  double h_min = 1e300, q_bias = 0.0;
  for (std::size_t k = 1; k + 1 < h.size(); ++k) {  // the inlet and exit corners aside
    h_min = std::min(h_min, h[k]);
    q_bias = std::max(q_bias, std::abs(q_adiabatic[k]));
  }
  std::printf("supersonic laminar wall: h min %.1f W/(m^2 K); adiabatic run's traced |q| up to "
              "%.0f W/m^2 (20 K probe)\n", h_min, q_bias);
  EXPECT_GT(h_min, 0.0);
  std::filesystem::remove_all(dir);
}
