// Every bad input of issue 3 exits 3 with one message that locates the problem (file:line, key,
// curve names, coordinates).
#include <gmsh.h>
#include <gtest/gtest.h>

#include "run_tool.hpp"

using tfmb::test::run_tool;
using tfmb::test::scratch_dir;
using tfmb::test::write_text;

namespace {

// Two straight flaps meeting at (1, 0.5); `second_start` moves the second flap's start.
std::string two_flap_csv(const std::string& second_start) {
  return "curve,x,y\nc1,0,0.5\nc1,1,0.5\nc2," + second_start + "\nc2,2,0.6\n";
}

std::string case_text(const std::string& geometry, const std::string& extra_flap_key = "",
                      const std::string& joint_extra = "") {
  return "[geometry]\nfile = \"" + geometry + "\"\ntolerance = 1e-6\n"
         "[[flap]]\nname = \"a\"\ncurves = [\"c1\"]\nthickness = 0.01\nmaterial = \"m\"\n"
         "youngs_modulus = 1e11\ndensity = 4000\n" + extra_flap_key +
         "[[flap]]\nname = \"b\"\ncurves = [\"c2\"]\nthickness = 0.01\nmaterial = \"m\"\n"
         "youngs_modulus = 1e11\ndensity = 4000\n"
         "[[joint]]\nname = \"hinge\"\nkind = \"revolute\"\nflaps = [\"a\", \"b\"]\n" + joint_extra +
         "[domain]\nkind = \"none\"\n";
}

tfmb::test::ToolResult run_case(const std::filesystem::path& dir, const std::string& csv,
                                const std::string& toml, const std::string& geometry = "g.csv") {
  if (!csv.empty()) write_text(dir / geometry, csv);
  write_text(dir / "case.toml", toml);
  return run_tool("tfmb-input " + (dir / "case.toml").string() + " -o " + (dir / "model.h5").string(), dir);
}

}  // namespace

TEST(BadInput, GoodCaseRuns) {
  const auto dir = scratch_dir("input-good");
  const auto r = run_case(dir, two_flap_csv("1,0.5"), case_text("g.csv"));
  EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(run_tool("tfmb-check --no-summary " + (dir / "model.h5").string(), dir).exit_code, 0);
}

TEST(BadInput, GapNamesBothCurvesAndTheLocation) {
  const auto dir = scratch_dir("input-gap");
  const auto r = run_case(dir, two_flap_csv("1.002,0.5"), case_text("g.csv"));
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.stderr_text.find("gap of 0.002 m"), std::string::npos) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("curve 'c1'"), std::string::npos) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("curve 'c2'"), std::string::npos) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("(1, 0.5)"), std::string::npos) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("case.toml:"), std::string::npos) << r.stderr_text;
}

TEST(BadInput, OverlapNamesBothCurvesAndTheLocation) {
  const auto dir = scratch_dir("input-overlap");
  // c2 starts 3 mm before the end of c1, on c1.
  const auto r = run_case(dir, two_flap_csv("0.997,0.5"), case_text("g.csv"));
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.stderr_text.find("overlap of 0.003 m"), std::string::npos) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("curve 'c1'"), std::string::npos) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("(0.997, 0.5)"), std::string::npos) << r.stderr_text;
}

TEST(BadInput, CrossingFlapsAreAnOverlap) {
  const auto dir = scratch_dir("input-cross");
  // c2 starts at c1's end but swings back across c1.
  const auto r = run_case(dir, "curve,x,y\nc1,0,0.5\nc1,1,0.5\nc2,1,0.5\nc2,1.2,0.7\nc2,0.5,0.3\n",
                          case_text("g.csv"));
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.stderr_text.find("overlap: flap 'a' (curve 'c1') and flap 'b' (curve 'c2') cross at ("),
            std::string::npos) << r.stderr_text;
}

TEST(BadInput, SelfIntersectingWall) {
  const auto dir = scratch_dir("input-self");
  const auto r = run_case(dir, "curve,x,y\nc1,0,0.5\nc1,1,0.5\nc1,1,0.7\nc1,0.5,0.3\nc2,0.5,0.3\nc2,2,0.6\n",
                          case_text("g.csv"));
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.stderr_text.find("self-intersecting wall: flap 'a' (curves c1) crosses itself at (0.75, 0.5)"),
            std::string::npos) << r.stderr_text;
}

TEST(BadInput, JointNotAtAFlapEnd) {
  const auto dir = scratch_dir("input-joint");
  const auto r = run_case(dir, two_flap_csv("1,0.5"), case_text("g.csv", "", "point = [0.5, 0.5]\n"));
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.stderr_text.find("joint 'hinge' at (0.5, 0.5) is not at an end of flap 'a' (nearest end"),
            std::string::npos) << r.stderr_text;
}

TEST(BadInput, UnknownKeyNamesTheKeyAndLine) {
  const auto dir = scratch_dir("input-key");
  const auto r = run_case(dir, two_flap_csv("1,0.5"), case_text("g.csv", "thikness = 0.01\n"));
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.stderr_text.find("case.toml:"), std::string::npos) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("unknown key 'flap[0].thikness'"), std::string::npos) << r.stderr_text;
}

TEST(BadInput, UnknownKeyThroughSetIsRefusedToo) {
  const auto dir = scratch_dir("input-set");
  write_text(dir / "g.csv", two_flap_csv("1,0.5"));
  write_text(dir / "case.toml", case_text("g.csv"));
  const auto r = run_tool("tfmb-input " + (dir / "case.toml").string() + " -o " + (dir / "m.h5").string() +
                              " --set flow.npr=3",
                          dir);
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.stderr_text.find("unknown key 'flow.npr'"), std::string::npos) << r.stderr_text;
}

TEST(BadInput, OutOfRangeValue) {
  const auto dir = scratch_dir("input-range");
  const auto r = run_case(dir, two_flap_csv("1,0.5"), case_text("g.csv") + "[flow]\ngamma = 3.0\n");
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.stderr_text.find("flow.gamma: = 3 outside the allowed range [1.01, 2]"), std::string::npos)
      << r.stderr_text;
}

TEST(BadInput, MissingGeometryFile) {
  const auto dir = scratch_dir("input-missing");
  const auto r = run_case(dir, "", case_text("nowhere.csv"));
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.stderr_text.find("nowhere.csv: geometry file not found"), std::string::npos) << r.stderr_text;
}

TEST(BadInput, StepWithoutCurves) {
  const auto dir = scratch_dir("input-step");
  {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::model::add("points");
    gmsh::model::occ::addPoint(0, 0, 0);
    gmsh::model::occ::addPoint(1, 0, 0);
    gmsh::model::occ::synchronize();
    gmsh::write((dir / "points.step").string());
    gmsh::finalize();
  }
  write_text(dir / "case.toml", case_text("points.step"));
  const auto r = run_tool("tfmb-input " + (dir / "case.toml").string() + " -o " + (dir / "m.h5").string(), dir);
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.stderr_text.find("points.step: the geometry holds no curves"), std::string::npos) << r.stderr_text;
}

// Flexible joints: lambda/mu choices are the seed's named ones or polynomial terms that keep its
// small-motion limits (mu -> 1, lambda -> 0); anything else exits 3 naming the key.
TEST(BadInput, FlexibleJointMeasureFunctions) {
  auto flexible = [](const std::string& extra) {
    std::string t = case_text("g.csv", "",
                              "stiffness_matrix = [[1e3,0,0,0,0,0],[0,1e3,0,0,0,0],[0,0,1e3,0,0,0],"
                              "[0,0,0,1e2,0,0],[0,0,0,0,1e2,0],[0,0,0,0,0,1e2]]\n" + extra);
    t.replace(t.find("kind = \"revolute\""), 17, "kind = \"flexible\"");
    return t;
  };
  const auto good = scratch_dir("input-flexible-good");
  const auto r = run_case(good, two_flap_csv("1,0.5"), flexible("measure_functions = \"2c\"\n"));
  EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
  const auto custom = scratch_dir("input-flexible-custom");
  const auto c = run_case(custom, two_flap_csv("1,0.5"),
                          flexible("measure_functions = \"custom\"\nmeasure_mu_terms = [[1, 0, 0], [0.5, 1, 2]]\n"));
  EXPECT_EQ(c.exit_code, 0) << c.stderr_text;
  EXPECT_EQ(run_tool("tfmb-check --no-summary " + (custom / "model.h5").string(), custom).exit_code, 0);
  const auto bad = scratch_dir("input-flexible-bad");
  const auto b = run_case(bad, two_flap_csv("1,0.5"),
                          flexible("measure_functions = \"custom\"\nmeasure_mu_terms = [[2, 0, 0]]\n"));
  EXPECT_EQ(b.exit_code, 3);
  EXPECT_NE(b.stderr_text.find("measure_mu_terms"), std::string::npos) << b.stderr_text;
  EXPECT_NE(b.stderr_text.find("mu -> 1"), std::string::npos) << b.stderr_text;
  const auto odd = scratch_dir("input-flexible-odd");
  const auto o = run_case(odd, two_flap_csv("1,0.5"),
                          flexible("measure_functions = \"custom\"\nmeasure_mu_terms = [[1, 0, 0], [1, 0, 1]]\n"));
  EXPECT_EQ(o.exit_code, 3);
  EXPECT_NE(o.stderr_text.find("odd power"), std::string::npos) << o.stderr_text;
}

// Joints and supports share /joints in structure.h5: a support named like a joint is refused.
TEST(BadInput, SupportNamedLikeAJoint) {
  const auto dir = scratch_dir("input-names");
  const auto r = run_case(dir, two_flap_csv("1,0.5"),
                          case_text("g.csv") + "[[support]]\nname = \"hinge\"\nflap = \"a\"\nend = \"start\"\nkind = \"clamp\"\n");
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.stderr_text.find("'hinge' is already used"), std::string::npos) << r.stderr_text;
}

// A sliding support's axis must not be zero; a clamp or pin has no axis (unknown key).
TEST(BadInput, SlidingSupportAxis) {
  auto support = [](const std::string& kind, const std::string& extra) {
    return case_text("g.csv") +
           "[[support]]\nname = \"s\"\nflap = \"a\"\nend = \"start\"\nkind = \"" + kind + "\"\n" +
           extra;
  };
  const auto good = scratch_dir("input-sliding-good");
  EXPECT_EQ(run_case(good, two_flap_csv("1,0.5"), support("sliding_pinned", "")).exit_code, 0);
  const auto zero = scratch_dir("input-sliding-zero");
  const auto z = run_case(zero, two_flap_csv("1,0.5"), support("sliding_clamp", "axis = [0, 0]\n"));
  EXPECT_EQ(z.exit_code, 3);
  EXPECT_NE(z.stderr_text.find("zero length"), std::string::npos) << z.stderr_text;
  const auto clamp = scratch_dir("input-sliding-clamp");
  const auto c = run_case(clamp, two_flap_csv("1,0.5"), support("clamp", "axis = [1, 0]\n"));
  EXPECT_EQ(c.exit_code, 3);
  EXPECT_NE(c.stderr_text.find("axis"), std::string::npos) << c.stderr_text;
}

// Prismatic joints need their sliding direction.
TEST(BadInput, PrismaticJointAxis) {
  auto prismatic = [](const std::string& extra) {
    std::string t = case_text("g.csv", "", extra);
    t.replace(t.find("kind = \"revolute\""), 17, "kind = \"prismatic\"");
    return t;
  };
  const auto good = scratch_dir("input-prismatic-good");
  const auto r = run_case(good, two_flap_csv("1,0.5"), prismatic("axis = [1, 0.1]\n"));
  EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(run_tool("tfmb-check --no-summary " + (good / "model.h5").string(), good).exit_code, 0);
  const auto bad = scratch_dir("input-prismatic-bad");
  const auto b = run_case(bad, two_flap_csv("1,0.5"), prismatic("axis = [0, 0]\n"));
  EXPECT_EQ(b.exit_code, 3);
  EXPECT_NE(b.stderr_text.find("axis"), std::string::npos) << b.stderr_text;
}

// A NaN coordinate and a point given twice in a row were refused only later as "its curves have
// zero length", naming neither the file nor the line.
TEST(BadInput, NonFiniteAndRepeatedPointsNameTheFileLine) {
  const auto dir = scratch_dir("input-nan-point");
  auto r =
      run_case(dir, "curve,x,y\nc1,0,0.5\nc1,nan,0.5\nc2,1,0.5\nc2,2,0.6\n", case_text("g.csv"));
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.stderr_text.find("g.csv:3: x and y must be finite"), std::string::npos)
      << r.stderr_text;
  r = run_case(dir, "curve,x,y\nc1,0,0.5\nc1,1,0.5\nc1,1,0.5\nc2,1,0.5\nc2,2,0.6\n",
               case_text("g.csv"));
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.stderr_text.find("g.csv:4: repeats the previous point of curve 'c1'"),
            std::string::npos)
      << r.stderr_text;
}
