// Verification of the nonlinear statics against closed forms and published benchmarks
// (FORMULATION.md sec. 5; refdata/beam CSVs).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "refdata.hpp"
#include "tfmb-beam/assembly.hpp"
#include "tfmb-beam/cases.hpp"
#include "tfmb-beam/rotation_wm.hpp"
#include "tfmb-beam/static_solver.hpp"

using namespace tfmb::beam;

namespace {

struct Tip {
  Eigen::Vector3d position;
  bool converged;
};

}  // namespace

// Cantilever rolled up by an end moment M = lam 2 pi EI / L: the axis is a circle of radius
// EI/M; at lam = 1 the tip returns to the root (full circle), at lam = 2 after two turns.
// Simo & Vu-Quoc's data: L = 1, EI = 2. The extensible, shear-deformable beam has the same closed
// form because pure bending produces no axial or shear force (refdata CSV header).
TEST(StaticsVerification, EndMomentRollUpFullCircleAndTwoTurns) {
  const double length = 1.0, ei = 2.0;
  const Section sec = make_diagonal_section(1e4, 1e4, 1e4, 2.0, ei, ei);
  const auto table = beam_test::read_table(beam_test::refdata_dir() + "/cantilever_end_moment_analytic.csv");
  for (const double lam_final : {1.0, 2.0}) {
    const int n_elements = lam_final > 1.0 ? 80 : 40;
    Model m = cases::cantilever(length, n_elements, sec);
    const int tip = static_cast<int>(m.nodes.size()) - 1;
    m.nodal_loads.push_back({tip, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 2 * M_PI * ei / length), false});
    Assembly asmb(m);
    StaticOptions opt;
    opt.final_load_factor = lam_final;
    opt.initial_steps = static_cast<int>(4 * lam_final);
    double worst_csv = 0.0;
    opt.on_step = [&](double lam, const State& s) {
      // Compare against the CSV rows at the load levels we pass through (lam <= 1).
      for (const auto& row : table.rows)
        if (std::abs(row[table.col("lam")] - lam) < 1e-12) {
          const Eigen::Vector2d exact(row[table.col("x_over_L")], row[table.col("y_over_L")]);
          worst_csv = std::max(worst_csv, (s.position[tip].head<2>() / length - exact).norm());
        }
    };
    const StaticResult r = solve_static(asmb, asmb.initial_state(), opt);
    ASSERT_TRUE(r.converged) << "lam " << lam_final;
    // Closed form at lam = 1 and 2: the tip is back at the root, rotated by 2 pi lam.
    const Eigen::Vector3d x = r.state.position[tip];
    EXPECT_LT(x.norm() / length, 1e-6) << "lam " << lam_final << " tip " << x.transpose();
    // Tip rotation: back to the reference frame after 2 pi lam; error relative to the total angle.
    const double angle_error = wm_angle(wm_from_rotation(asmb.frame(r.state, tip)));
    EXPECT_LT(angle_error / (2 * M_PI * lam_final), 1e-6);
    EXPECT_LT(worst_csv, 1e-6) << "intermediate load levels";
    std::cout << "[roll-up] lam " << lam_final << ": " << n_elements << " elements, " << r.steps << " steps, "
              << r.iterations << " Newton iterations, |tip|/L = " << x.norm() / length << ", worst CSV error "
              << worst_csv << "\n";
  }
}

// The roll-up asked in one load step: one, two and four turns (M = 8 pi EI / L, as Simo & Vu-Quoc
// 1986, Part II, converge in one step). Full Newton corrections with the exact tangent converge it
// (12, 13 and 18 iterations); the 0.25 rad cap alone took 41 to 240 iterations and, at four turns,
// a cut-back to two steps.
TEST(StaticsVerification, EndMomentRollUpInOneLoadStep) {
  const double length = 1.0, ei = 2.0;
  const Section sec = make_diagonal_section(1e4, 1e4, 1e4, 2.0, ei, ei);
  for (const double turns : {1.0, 2.0, 4.0}) {
    Model m = cases::cantilever(length, 80, sec);
    const int tip = static_cast<int>(m.nodes.size()) - 1;
    m.nodal_loads.push_back(
        {tip, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 2 * M_PI * ei / length), false});
    Assembly asmb(m);
    StaticOptions opt;
    opt.final_load_factor = turns;
    opt.initial_steps = 1;
    const StaticResult r = solve_static(asmb, asmb.initial_state(), opt);
    ASSERT_TRUE(r.converged) << turns << " turns";
    EXPECT_EQ(r.steps, 1) << turns << " turns";
    EXPECT_EQ(r.cutbacks, 0) << turns << " turns";
    EXPECT_LE(r.iterations, 20) << turns << " turns";
    // Tip back at the root: the discretisation error of 80 elements grows as (h kappa)^2, 7.9e-8
    // at one turn, 1.3e-6 at four.
    EXPECT_LT(r.state.position[tip].norm() / length, 2e-6 * turns * turns / 16.0 + 1e-7)
        << turns << " turns";
    std::cout << "[roll-up, one step] " << turns << " turns: " << r.iterations
              << " Newton iterations\n";
  }
}

// Tip-load elastica (Bisshopp & Drucker): inextensible, shear-rigid reference; EA and GA are
// 1e7 times the bending scale so their compliance (~1e-7) is far below the 0.1 % tolerance.
TEST(StaticsVerification, TipLoadElasticaWithinPointOnePercent) {
  const double length = 1.0, ei = 1.0;
  const Section sec = make_diagonal_section(1e7, 1e7, 1e7, 1.0, ei, ei);
  const auto table = beam_test::read_table(beam_test::refdata_dir() + "/cantilever_tip_load_elastica.csv");
  int checked = 0;
  double worst = 0.0;
  for (const auto& row : table.rows) {
    const double k = row[table.col("k")];
    if (k != 0.5 && k != 1.0 && k != 2.0 && k != 5.0 && k != 10.0 && k != 20.0) continue;
    Model m = cases::cantilever(length, 16, sec);
    const int tip = static_cast<int>(m.nodes.size()) - 1;
    m.nodal_loads.push_back({tip, Eigen::Vector3d(0, -k * ei / (length * length), 0), Eigen::Vector3d::Zero(), false});
    Assembly asmb(m);
    const StaticResult r = solve_static(asmb, asmb.initial_state());
    ASSERT_TRUE(r.converged) << "k = " << k;
    const double v = -r.state.position[tip].y() / length;
    const double u = 1.0 - r.state.position[tip].x() / length;
    const double v_ref = row[table.col("v_over_L")], u_ref = row[table.col("u_over_L")];
    EXPECT_LT(std::abs(v - v_ref) / v_ref, 1e-3) << "k = " << k;
    EXPECT_LT(std::abs(u - u_ref) / u_ref, 1e-3) << "k = " << k;
    worst = std::max({worst, std::abs(v - v_ref) / v_ref, std::abs(u - u_ref) / u_ref});
    ++checked;
  }
  EXPECT_EQ(checked, 6);
  std::cout << "[elastica] 16 elements, " << checked << " load levels, worst relative error " << worst << "\n";
}

// 45-degree bend, tip position against Simo & Vu-Quoc (1986) at P = 300, 450, 600 within 0.5 %
// (norm of the position difference over the norm of the reference position; the clamp is at the
// origin). The 450 row is marked UNVERIFIED-recalled in the CSV; it is checked all the same.
TEST(StaticsVerification, Bend45AgainstSimoVuQuoc) {
  const auto table = beam_test::read_table(beam_test::refdata_dir() + "/bend45_tip_positions.csv");
  // Section data of the beam references (GXBeam/Simo-Vu-Quoc lineage): shear factor 1 and
  // J = I2 + I3 = 1/6 (FORMULATION.md sec. 2: the references differ here).
  Model m = cases::bend45(16, 600.0, 1.0, 1.0 / 6.0);
  const int tip = static_cast<int>(m.nodes.size()) - 1;
  Assembly asmb(m);
  StaticOptions opt;
  opt.initial_steps = 4;  // 150, 300, 450, 600 (the solver may cut back)
  std::vector<std::pair<double, Eigen::Vector3d>> tips;
  opt.on_step = [&](double lf, const State& s) { tips.push_back({600.0 * lf, s.position[tip]}); };
  const StaticResult r = solve_static(asmb, asmb.initial_state(), opt);
  ASSERT_TRUE(r.converged);
  int checked = 0;
  for (size_t i = 0; i < table.rows.size(); ++i) {
    if (table.text[i][0].find("Simo & Vu-Quoc") == std::string::npos) continue;
    const double p = table.rows[i][table.col("P")];
    const Eigen::Vector3d ref(table.rows[i][table.col("x")], table.rows[i][table.col("y")],
                              table.rows[i][table.col("z")]);
    for (const auto& [load, x] : tips)
      if (std::abs(load - p) < 1e-9) {
        // Tip position error relative to the tip position (distance from the clamp).
        const double err = (x - ref).norm() / ref.norm();
        EXPECT_LT(err, 5e-3) << "P " << p;
        std::cout << "[bend45] P " << p << ": ours " << x.transpose() << "  Simo-Vu-Quoc " << ref.transpose()
                  << "  relative error " << err << "\n";
        ++checked;
      }
  }
  EXPECT_EQ(checked, 3);
}

// The same bend against CalculiX's converged 64-element B32R run. Finding: CalculiX's tips agree
// with our J = 1/6, k = 1 section to ~1e-4, while J = 0.1406, k = 5/6 (which the CSV header
// expects for the expanded bricks) moves our tip by ~0.5 % towards the Kynema/Cardona rows. So the
// comparison uses J = 1/6, k = 1; tolerance 0.1 % covers CalculiX's own mesh error (~1e-4).
TEST(StaticsVerification, Bend45AgainstConvergedCalculix) {
  const auto table = beam_test::read_table(beam_test::refdata_dir() + "/calculix/bend45_calculix_results.csv");
  Model m = cases::bend45(16, 600.0, 1.0, 1.0 / 6.0);
  const int tip = static_cast<int>(m.nodes.size()) - 1;
  Assembly asmb(m);
  StaticOptions opt;
  opt.initial_steps = 4;
  std::vector<std::pair<double, Eigen::Vector3d>> tips;
  opt.on_step = [&](double lf, const State& s) { tips.push_back({600.0 * lf, s.position[tip]}); };
  const StaticResult r = solve_static(asmb, asmb.initial_state(), opt);
  ASSERT_TRUE(r.converged);
  int checked = 0;
  for (const auto& row : table.rows) {
    if (row[table.col("nelem_B32R")] != 64) continue;
    const Eigen::Vector3d ref(row[table.col("x")], row[table.col("y")], row[table.col("z")]);
    for (const auto& [load, x] : tips)
      if (std::abs(load - row[table.col("load")]) < 1e-9) {
        const double err = (x - ref).norm() / ref.norm();
        EXPECT_LT(err, 1e-3) << "P " << load;
        std::cout << "[bend45-ccx] P " << load << ": ours " << x.transpose() << "  CalculiX-64 " << ref.transpose()
                  << "  relative error " << err << "\n";
        ++checked;
      }
  }
  EXPECT_EQ(checked, 3);
}

// Thermal strain and curvature as initial strains: a free-ended cantilever expands by
// eps_T L and bends into a circular arc of curvature k_T (no stress anywhere), so the tip sits at
// (sin(k L)/k, (1 - cos(k L))/k) scaled by (1 + eps_T) -- exact for any magnitude.
TEST(StaticsVerification, ThermalStrainAndCurvature) {
  const double length = 2.0, eps_t = 1e-3, k_t = 0.8;  // 1.6 rad of thermal bending
  Model m = cases::cantilever(length, 20, make_diagonal_section(1e5, 1e5, 1e5, 10.0, 20.0, 20.0));
  for (auto& el : m.elements) {
    el.initial_strain(0) = eps_t;
    el.initial_strain(5) = k_t;
  }
  Assembly asmb(m);
  const StaticResult r = solve_static(asmb, asmb.initial_state());
  ASSERT_TRUE(r.converged);
  const Eigen::Vector3d tip = r.state.position.back();
  const double s = (1 + eps_t) * length;
  const Eigen::Vector3d exact(std::sin(k_t * length) / k_t * (1 + eps_t), (1 - std::cos(k_t * length)) / k_t * (1 + eps_t), 0.0);
  // Curvature of the stretched arc: k_T / (1 + eps_T) per unit deformed length gives the same
  // total angle k_T L; the 20-element mesh error is ~1e-7.
  (void)s;
  EXPECT_LT((tip - exact).norm() / length, 1e-6) << tip.transpose() << " vs " << exact.transpose();
  std::vector<ElementResult> er;
  asmb.element_results(r.state, er);
  double max_force = 0.0;
  for (const auto& e : er)
    for (const auto& st : e.stress) max_force = std::max(max_force, st.cwiseAbs().maxCoeff());
  EXPECT_LT(max_force, 1e-8);
}

// Snap-through of a shallow two-bar (von Mises) truss built from beams with pinned ends: the bars
// carry only axial force N = EA (L - L0)/L0, so the apex load on the path is
// P(w) = 2 EA (L0 - L)(h - w) / (L0 L), L = sqrt(a^2 + (h - w)^2). Load control stops at the limit
// point; arc length follows the path through it to the inverted shape.
TEST(StaticsVerification, ArcLengthThroughLimitPoint) {
  const double a = 1.0, h = 0.2, ea = 1e4;
  Model m;
  m.sections.push_back(make_diagonal_section(ea, 1e4, 1e4, 10.0, 10.0, 10.0));
  const auto left = add_beam(
      m, 2, 0, [&](double s) { return Eigen::Vector3d(-a + a * s, h * s, 0.0); },
      [&](double) { return Eigen::Vector3d(a, h, 0.0); });
  const auto right = add_beam(
      m, 2, 0, [&](double s) { return Eigen::Vector3d(a * s, h - h * s, 0.0); },
      [&](double) { return Eigen::Vector3d(a, -h, 0.0); });
  auto hinge = [&](const std::string& name, int na, int nb) {
    JointSpec j;
    j.kind = JointKind::revolute;
    j.name = name;
    j.node_a = na;
    j.node_b = nb;
    m.joints.push_back(j);
  };
  hinge("left support", -1, left.front());
  hinge("right support", -1, right.back());
  hinge("apex", left.back(), right.front());
  add_planar_constraints(m);
  const int apex = left.back();
  m.nodal_loads.push_back({apex, Eigen::Vector3d(0, -1.0, 0), Eigen::Vector3d::Zero(), false});
  Assembly asmb(m);
  const double l0 = std::sqrt(a * a + h * h);
  auto exact = [&](double w) {
    const double l = std::sqrt(a * a + (h - w) * (h - w));
    return 2.0 * ea * (l0 - l) * (h - w) / (l0 * l);
  };
  double worst = 0.0, w_max = 0.0, p_max = 0.0;
  ArcLengthOptions opt;
  opt.initial_load_increment = 5.0;
  opt.final_load_factor = 1e9;
  opt.max_displacement = 1.6 * h;
  opt.on_step = [&](double p, const State& s) {
    const double w = m.nodes[apex].position.y() - s.position[apex].y();
    worst = std::max(worst, std::abs(p - exact(w)) / 30.0);
    w_max = std::max(w_max, w);
    p_max = std::max(p_max, p);
  };
  const StaticResult r = solve_arc_length(asmb, asmb.initial_state(), opt);
  ASSERT_TRUE(r.converged) << "stopped at load factor " << r.load_factor;
  EXPECT_GT(w_max, 1.5 * h);  // through the limit point and the unstable branch
  // Load error relative to the order of the limit load (32.4 here): Newton tolerance.
  EXPECT_LT(worst, 1e-6);
  std::cout << "[arc length] " << r.steps << " steps, " << r.iterations << " iterations, max load " << p_max
            << ", apex travel " << w_max << " m, worst |P - P(w)| / 30 = " << worst << "\n";
}

namespace {

/// Distance from point p to the polyline through pts (all in the same scaled coordinates).
double distance_to_polyline(const Eigen::Vector3d& p, const std::vector<Eigen::Vector3d>& pts) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    const Eigen::Vector3d d = pts[i + 1] - pts[i];
    const double t =
        d.squaredNorm() > 0.0 ? std::clamp((p - pts[i]).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    best = std::min(best, (p - pts[i] - t * d).norm());
  }
  return best;
}

}  // namespace

// Lee's frame under a dead load past its limit load, traced by arc length from a coarse start
// (first step 1/10 of the load, as a 10-step load-controlled run would take): through the limit
// point in load (snap-through), the limit point in displacement (snap-back, the load point's
// downward travel turns back) and the unloading branch back up to the full load.
// Reference: (1) the published limit load of the dead-load path, 18532 (Simo & Vu-Quoc 1986,
// Part II; refdata/beam/FORMULATION.md sec. 2); (2) the path after the limit point has no
// digitised published counterpart in refdata, so the coarse path is compared with a converged
// fine-arc run of the same solver and model (1/50 of the load per step, arc not allowed to grow).
TEST(StaticsVerification, LeeFrameThroughLimitPointsInLoadAndDisplacement) {
  const double load = 20000.0, length = 120.0, published_limit = 18532.0;
  const auto frame = cases::lee_frame(10, load);
  Assembly asmb(frame.model);
  auto trace = [&](double first_increment, double max_arc_factor) {
    ArcLengthOptions opt;
    opt.initial_load_increment = first_increment;
    opt.max_arc_factor = max_arc_factor;
    opt.max_steps = 2000;
    opt.max_displacement = 2.0 * length;
    opt.monitor = {frame.load_node, Eigen::Vector3d(0.0, -1.0, 0.0)};
    return solve_arc_length(asmb, asmb.initial_state(), opt);
  };
  const StaticResult coarse = trace(0.1, 4.0);
  const StaticResult fine = trace(0.02, 1.0);
  ASSERT_TRUE(fine.converged) << "fine run stopped at load factor " << fine.load_factor;
  ASSERT_TRUE(coarse.converged) << "coarse run stopped at load factor " << coarse.load_factor;
  EXPECT_DOUBLE_EQ(coarse.load_factor, 1.0);
  EXPECT_DOUBLE_EQ(fine.load_factor, 1.0);
  // Scaled path coordinates: horizontal and downward displacement of the load point over the
  // member length, load over the published limit load.
  auto scaled = [&](const PathPoint& p) {
    return Eigen::Vector3d(p.node_displacement.x() / length, -p.node_displacement.y() / length,
                           p.load_factor * load / published_limit);
  };
  std::vector<Eigen::Vector3d> fine_pts;
  for (const auto& p : fine.path)
    fine_pts.push_back(scaled(p));
  double worst = 0.0;
  for (const auto& p : coarse.path)
    worst = std::max(worst, distance_to_polyline(scaled(p), fine_pts));
  const LimitPoints coarse_limits = find_limit_points(coarse.path),
                    fine_limits = find_limit_points(fine.path);
  ASSERT_FALSE(fine_limits.load.empty());
  const double fine_limit =
      fine.path[static_cast<std::size_t>(fine_limits.load.front())].load_factor * load;
  ASSERT_FALSE(coarse_limits.load.empty());
  const double coarse_limit =
      coarse.path[static_cast<std::size_t>(coarse_limits.load.front())].load_factor * load;
  std::cout << "[Lee frame] coarse: " << coarse.steps << " steps, " << coarse.iterations
            << " iterations, " << coarse.cutbacks << " cut-backs, limit points in load "
            << coarse_limits.load.size() << ", in displacement "
            << coarse_limits.displacement.size() << "; fine: " << fine.steps
            << " steps, limit points " << fine_limits.load.size() << " / "
            << fine_limits.displacement.size() << "; first limit load fine " << fine_limit
            << ", coarse " << coarse_limit
            << "; worst scaled distance of the coarse path from the fine one " << worst << "\n";
  // The coarse run keeps to the fine run's branch all the way: its converged states lie on the
  // fine polyline within the fine run's chord error (the fine arc is about 1/50 of the load
  // increment's, its chords sag by ~1e-6 of the scale on the curved parts).
  EXPECT_LT(worst, 1e-4);
  // Both turns of the load (the limit load and the minimum on the unloading branch) and both
  // turns of the load point's downward travel (the snap-back and its return) on either run.
  EXPECT_EQ(fine_limits.load.size(), 2u);
  EXPECT_EQ(fine_limits.displacement.size(), 2u);
  EXPECT_EQ(coarse_limits.load.size(), fine_limits.load.size());
  EXPECT_EQ(coarse_limits.displacement.size(), fine_limits.displacement.size());
  // Published limit load within 0.5 %: Simo & Vu-Quoc's mesh and element differ from ours (10
  // quadratic elements per member); the fine run's peak row lies within ~1e-5 of the peak.
  EXPECT_NEAR(fine_limit / published_limit, 1.0, 5e-3);
  // The coarse run's limit row is the converged state nearest the peak, not the peak itself.
  EXPECT_NEAR(coarse_limit / fine_limit, 1.0, 1e-2);
  // Each path row is a converged state: the recorded iterations are the Newton iterations.
  int iterations = 0;
  for (const auto& p : coarse.path)
    iterations += p.iterations;
  EXPECT_EQ(iterations, coarse.iterations);
}

// Limit points are the rows where the load factor, or the characteristic displacement, turns.
TEST(StaticsPath, LimitPointsAreTheTurnsOfLoadAndDisplacement) {
  std::vector<PathPoint> path;
  const double lambdas[] = {0.0, 0.5, 0.9, 0.8, 0.3, 0.2, 0.6};
  const double displacements[] = {0.0, 1.0, 2.0, 3.0, 2.5, 2.0, 4.0};
  for (int i = 0; i < 7; ++i) {
    PathPoint p;
    p.load_factor = lambdas[i];
    p.characteristic_displacement = displacements[i];
    path.push_back(p);
  }
  const LimitPoints lp = find_limit_points(path);
  EXPECT_EQ(lp.load, (std::vector<int>{2, 5}));
  EXPECT_EQ(lp.displacement, (std::vector<int>{3, 5}));
  EXPECT_TRUE(find_limit_points({}).load.empty());
}

// Load stepping records its path too: the initial state, then one row per converged step.
TEST(StaticsPath, LoadSteppingRecordsEveryConvergedStep) {
  const Section sec = make_diagonal_section(1e4, 1e4, 1e4, 2.0, 2.0, 2.0);
  Model m = cases::cantilever(1.0, 8, sec);
  const int tip = static_cast<int>(m.nodes.size()) - 1;
  m.nodal_loads.push_back({tip, Eigen::Vector3d(0, -1.0, 0), Eigen::Vector3d::Zero(), false});
  Assembly asmb(m);
  StaticOptions opt;
  opt.initial_steps = 4;
  opt.monitor = {tip, Eigen::Vector3d(0, -1, 0)};
  const StaticResult r = solve_static(asmb, asmb.initial_state(), opt);
  ASSERT_TRUE(r.converged);
  ASSERT_EQ(r.path.size(), static_cast<std::size_t>(r.steps + 1));
  EXPECT_EQ(r.path.front().load_factor, 0.0);
  EXPECT_EQ(r.path.back().load_factor, 1.0);
  int iterations = 0;
  for (std::size_t i = 1; i < r.path.size(); ++i) {
    EXPECT_GT(r.path[i].load_factor, r.path[i - 1].load_factor);
    EXPECT_GT(r.path[i].arc_length, r.path[i - 1].arc_length);
    iterations += r.path[i].iterations;
  }
  EXPECT_EQ(iterations, r.iterations);
  const Eigen::Vector3d tip_u = r.state.position[tip] - m.nodes[tip].position;
  EXPECT_EQ(r.path.back().node_displacement, tip_u);
  EXPECT_DOUBLE_EQ(r.path.back().characteristic_displacement, -tip_u.y());
  // The tip moves most; the path of a monotonic response has no limit point.
  EXPECT_DOUBLE_EQ(r.path.back().max_displacement, tip_u.norm());
  EXPECT_TRUE(find_limit_points(r.path).load.empty());
  EXPECT_TRUE(find_limit_points(r.path).displacement.empty());
}

// The arc grows on easy steps but never beyond max_arc_factor times the first arc: on a nearly
// linear response (a cantilever under a small tip load, Newton in 1-2 iterations) the load-factor
// increment stays below 4 times the first one, while without the bound it doubles every step.
TEST(StaticsPath, ArcGrowthIsBounded) {
  const Section sec = make_diagonal_section(1e4, 1e4, 1e4, 2.0, 2.0, 2.0);
  Model m = cases::cantilever(1.0, 4, sec);
  const int tip = static_cast<int>(m.nodes.size()) - 1;
  m.nodal_loads.push_back({tip, Eigen::Vector3d(0, -1e-6, 0), Eigen::Vector3d::Zero(), false});
  Assembly asmb(m);
  auto largest_increment = [&](double max_arc_factor) {
    ArcLengthOptions opt;
    opt.initial_load_increment = 0.01;
    opt.max_arc_factor = max_arc_factor;
    const StaticResult r = solve_arc_length(asmb, asmb.initial_state(), opt);
    EXPECT_TRUE(r.converged);
    double largest = 0.0;
    for (std::size_t i = 1; i < r.path.size(); ++i)
      largest = std::max(largest, r.path[i].load_factor - r.path[i - 1].load_factor);
    return largest;
  };
  // Linear response: the load-factor increment is proportional to the arc (1e-6 relative).
  EXPECT_LE(largest_increment(4.0), 0.04 * (1 + 1e-6));
  EXPECT_GT(largest_increment(1e300), 0.1);
}
