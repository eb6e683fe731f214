// Unit tests of assembly-level behaviour: patch test on distorted mixed meshes, the consistent
// tangent against finite differences, contact, per-beam outputs and bad-input messages.
#include "heat_test_support.hpp"
#include "tfmb-heat/assembly.hpp"
#include "tfmb-heat/beam_outputs.hpp"
#include "tfmb-heat/heat_flux.hpp"
#include "tfmb-heat/steady_solver.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

using namespace tfmb::heat;
using namespace tfmb::heat::testing;

namespace {

Material constant_material(double k) {
  return {"constant", PropertyTable::constant(k), PropertyTable::constant(8000.0),
          PropertyTable::constant(500.0)};
}

Material table_material() {
  return {"table", PropertyTable({200, 400, 700, 1200}, {6.0, 9.0, 10.0, 17.0}),
          PropertyTable({200, 1200}, {4500, 4300}), PropertyTable({200, 600, 1200}, {500, 600, 750})};
}

SolidMesh distorted_mixed_mesh(ElementType quad_type, int cells) {
  StripMeshOptions o;
  o.length = 1.0;
  o.thickness = 1.0;
  o.cells_along = cells;
  o.cells_through = cells;
  o.type = quad_type;
  o.map = distort_unit_square;
  o.triangles_below_x = 0.5;
  return make_strip_mesh(o);
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "no exception";
}

}  // namespace

TEST(HeatPatchTest, LinearFieldIsReproducedOnDistortedMixedMeshes) {
  auto field = [](double x, double y) { return 300.0 + 20.0 * x - 10.0 * y; };
  for (auto type : {ElementType::quad4, ElementType::quad8, ElementType::quad9}) {
    const auto mesh = distorted_mixed_mesh(type, 4);
    ThermalProblem problem;
    problem.mesh = &mesh;
    problem.materials = {constant_material(15.0)};
    for (const char* side : {"bottom", "right", "top", "left"}) {
      problem.boundary_conditions.push_back({side, ImposedTemperature{trace_at_nodes(mesh, side, field)}});
    }
    const auto result = solve_steady(problem, 300.0);
    ASSERT_TRUE(result.newton.converged);
    double worst = 0;
    for (Eigen::Index i = 0; i < mesh.points.rows(); ++i) {
      worst = std::max(worst, std::abs(result.temperature[i] - field(mesh.points(i, 0), mesh.points(i, 1))));
    }
    // Exact up to rounding of a well-conditioned solve (values ~300 K).
    EXPECT_LT(worst, 1e-9) << element_name(type);
    // Recovered flux equals -k grad T everywhere.
    const auto flux = nodal_heat_flux(problem, result.temperature);
    EXPECT_NEAR(flux(7, 0), -15.0 * 20.0, 1e-7);
    EXPECT_NEAR(flux(7, 1), 15.0 * 10.0, 1e-7);
  }
}

TEST(HeatAssembly, ConsistentTangentMatchesFiniteDifferences) {
  for (auto type : {ElementType::quad4, ElementType::quad8, ElementType::quad9}) {
    auto a = distorted_mixed_mesh(type, 3);
    auto b = distorted_mixed_mesh(type, 2);
    for (Eigen::Index i = 0; i < b.points.rows(); ++i) b.points(i, 1) += 1.001;  // small gap
    const auto mesh = join_meshes(a, b, "a_", "b_");
    ThermalProblem problem;
    problem.mesh = &mesh;
    problem.materials = {table_material()};
    problem.boundary_conditions.push_back(
        {"a_bottom", Convection{dense_trace(1.0, 11, [](double s) { return 100 + 50 * s; }, "h"),
                                dense_trace(1.0, 11, [](double s) { return 900 - 200 * s; }, "Taw")}});
    problem.boundary_conditions.push_back({"b_top", Radiation{0.8, 300.0}});
    problem.contacts.push_back({"a_top", "b_bottom", 2000.0});
    problem.volumetric_source = [](double x, double y) { return 1e4 * (1 + x * y); };
    const Assembler assembler(problem, true);
    const auto n = static_cast<Eigen::Index>(assembler.dof_count());
    Eigen::VectorXd t(n), history(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      t[i] = 450.0 + 300.0 * std::sin(0.7 * static_cast<double>(i));
      history[i] = 30.0 * std::cos(0.3 * static_cast<double>(i));
    }
    const TimeTerm term{0.05, &history};
    Eigen::VectorXd r0, rp, rm;
    Eigen::SparseMatrix<double> k;
    assembler.assemble(t, term, r0, &k, Tangent::consistent);
    const Eigen::MatrixXd dense = Eigen::MatrixXd(k);
    const double h = 1e-4;
    double worst = 0, scale = dense.cwiseAbs().maxCoeff();
    for (Eigen::Index j = 0; j < n; ++j) {
      Eigen::VectorXd tp = t, tm = t;
      tp[j] += h;
      tm[j] -= h;
      assembler.assemble(tp, term, rp, nullptr, Tangent::consistent);
      assembler.assemble(tm, term, rm, nullptr, Tangent::consistent);
      worst = std::max(worst, (dense.col(j) - (rp - rm) / (2 * h)).cwiseAbs().maxCoeff());
    }
    // Central differences: error ~ h^2 |R'''| plus kinks of the piecewise-linear tables, which
    // the chosen temperatures avoid at the quadrature points only with high probability; the
    // bound is relative to the largest tangent entry.
    EXPECT_LT(worst / scale, 1e-6) << element_name(type);
  }
}

TEST(HeatContact, PerfectContactEqualsOneBody) {
  StripMeshOptions o;
  o.length = 0.2;
  o.thickness = 0.01;
  o.cells_along = 6;
  o.cells_through = 2;
  auto lower = make_strip_mesh(o);
  auto upper = make_strip_mesh(o);
  for (Eigen::Index i = 0; i < upper.points.rows(); ++i) upper.points(i, 1) += 0.01;
  const auto mesh = join_meshes(lower, upper, "lo_", "up_");
  ThermalProblem problem;
  problem.mesh = &mesh;
  problem.materials = {constant_material(12.0)};
  problem.boundary_conditions.push_back({"lo_bottom", ImposedTemperature{constant_trace(0.2, 500.0, "T")}});
  problem.boundary_conditions.push_back({"up_top", ImposedTemperature{constant_trace(0.2, 300.0, "T")}});
  problem.contacts.push_back({"lo_top", "up_bottom", std::nullopt});
  const auto result = solve_steady(problem, 400.0);
  ASSERT_TRUE(result.newton.converged);
  for (Eigen::Index i = 0; i < mesh.points.rows(); ++i) {
    EXPECT_NEAR(result.temperature[i], 500.0 - 200.0 * mesh.points(i, 1) / 0.02, 1e-9);
  }
}

TEST(HeatContact, GapConductanceGivesSeriesResistance) {
  StripMeshOptions o;
  o.length = 0.2;
  o.thickness = 0.01;
  o.cells_along = 5;
  o.cells_through = 2;
  auto lower = make_strip_mesh(o);
  o.cells_along = 7;  // non-matching interface
  auto upper = make_strip_mesh(o);
  for (Eigen::Index i = 0; i < upper.points.rows(); ++i) upper.points(i, 1) += 0.01;
  const auto mesh = join_meshes(lower, upper, "lo_", "up_");
  ThermalProblem problem;
  problem.mesh = &mesh;
  problem.materials = {constant_material(12.0)};
  problem.boundary_conditions.push_back({"lo_bottom", ImposedTemperature{constant_trace(0.2, 500.0, "T")}});
  problem.boundary_conditions.push_back({"up_top", ImposedTemperature{constant_trace(0.2, 300.0, "T")}});
  const double hc = 3000.0;
  problem.contacts.push_back({"lo_top", "up_bottom", hc});
  const auto result = solve_steady(problem, 400.0);
  ASSERT_TRUE(result.newton.converged);
  // q = dT / (t/k + 1/h_c + t/k), per unit area.
  const double q = 200.0 / (0.01 / 12.0 + 1.0 / hc + 0.01 / 12.0);
  const Assembler assembler(problem, false);
  const auto dofs = assembler.to_dofs(result.temperature);
  const auto rates = assembler.boundary_heat_rates(dofs, {});
  EXPECT_NEAR(rates.at("lo_bottom"), q * 0.2, 1e-9 * q);
  EXPECT_NEAR(rates.at("up_top"), -q * 0.2, 1e-9 * q);
  EXPECT_NEAR(assembler.contact_heat_rates(dofs)[0], q * 0.2, 1e-9 * q);
}

TEST(HeatBeamOutputs, LinearThroughThicknessField) {
  for (auto type : {ElementType::quad4, ElementType::quad8}) {
    StripMeshOptions o;
    o.length = 0.4;
    o.thickness = 0.008;
    o.cells_along = 16;
    o.cells_through = 4;
    o.type = type;
    o.triangles_below_x = 0.1;  // mixed
    const auto mesh = make_strip_mesh(o);
    const double gradient = 2500.0;  // [K/m]
    Eigen::VectorXd t(mesh.points.rows()), z(mesh.points.rows());
    for (Eigen::Index i = 0; i < t.size(); ++i) {
      z[i] = mesh.points(i, 1) - 0.5 * o.thickness;  // reference line at mid-thickness
      t[i] = 600.0 + 150.0 * mesh.points(i, 0) + gradient * z[i];
    }
    // Four beam elements, each a quarter of the strip.
    std::vector<std::int64_t> cell_to_beam;
    std::size_t cell = 0;
    for (const auto& block : mesh.blocks) {
      for (std::size_t e = 0; e < block.size(); ++e, ++cell) {
        double xc = 0;
        for (auto n : block.element(e)) xc += mesh.points(n, 0);
        xc /= static_cast<double>(block.element(e).size());
        cell_to_beam.push_back(static_cast<std::int64_t>(xc / 0.1));
      }
    }
    const auto out = beam_element_temperatures(mesh, t, cell_to_beam, z, 4);
    for (std::size_t b = 0; b < 4; ++b) {
      EXPECT_NEAR(out.area[b], 0.1 * o.thickness, 1e-15);
      EXPECT_NEAR(out.mean_temperature[b], 600.0 + 150.0 * (0.05 + 0.1 * static_cast<double>(b)), 1e-9);
      EXPECT_NEAR(out.temperature_gradient[b], gradient, 1e-6);
      EXPECT_NEAR(out.thickness[b], o.thickness, 1e-15);
      EXPECT_NEAR(out.temperature_difference[b], gradient * o.thickness, 1e-8);
      EXPECT_NEAR(out.z_centroid[b], 0.0, 1e-15);
    }
  }
}

TEST(HeatBadInput, MessagesNameTheProblem) {
  StripMeshOptions o;
  o.cells_along = 4;
  o.cells_through = 1;
  const auto mesh = make_strip_mesh(o);
  ThermalProblem problem;
  problem.mesh = &mesh;
  problem.materials = {{"zero-k", PropertyTable({300, 600}, {0.0, 5.0}), {}, {}}};
  problem.boundary_conditions.push_back({"left", ImposedTemperature{constant_trace(0.01, 500, "T")}});
  EXPECT_NE(error_of([&] { solve_steady(problem, 400); }).find("conductivity"), std::string::npos);

  problem.materials = {{"narrow", PropertyTable({300, 450}, {5.0, 6.0}), {}, {}}};
  const auto range_error = error_of([&] { solve_steady(problem, 400); });
  EXPECT_NE(range_error.find("outside the property table of material 'narrow'"), std::string::npos) << range_error;

  problem.materials = {constant_material(5.0)};
  problem.boundary_conditions = {{"right", Convection{{}, constant_trace(0.01, 300, "Taw")}}};
  const auto trace_error = error_of([&] { solve_steady(problem, 400); });
  EXPECT_NE(trace_error.find("boundary 'right' (convection): needs a heat transfer coefficient trace"), std::string::npos) << trace_error;

  problem.boundary_conditions = {{"nozzle", Radiation{0.5, 300}}};
  EXPECT_NE(error_of([&] { solve_steady(problem, 400); }).find("no boundary 'nozzle'"), std::string::npos);

  // A trace shorter than the wall does not cover it.
  problem.boundary_conditions = {{"bottom", ImposedTemperature{constant_trace(0.5, 500, "T")}}};
  EXPECT_NE(error_of([&] { solve_steady(problem, 400); }).find("outside the trace"), std::string::npos);
}
