// tfmb-loads end to end on files written by the tests: outputs validate against their
// schemas, totals are printed, bad inputs exit 3 with a located message.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <Eigen/Geometry>

#include "tfmb-loads/run.hpp"
#include "test_files.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/formats/schema.hpp"

using namespace tfmb;
using namespace tfmb::loads;
using tfmb::testfiles::Vec2;
namespace tf = tfmb::testfiles;

namespace {

const Logger quiet("test", Verbosity::quiet);

std::vector<std::string> problems(const std::filesystem::path& file, const std::string& kind) {
  const h5::Reader reader(file);
  std::vector<std::string> out;
  for (const auto& p : formats::validate(reader, *formats::find_schema(kind))) out.push_back(p.object_path + ": " + p.message);
  return out;
}

// Two straight flaps; inner fluid on the right of the point order, outer on the left.
struct Files {
  std::filesystem::path dir, model, flow;
  std::vector<tf::TestFlap> flaps;
  explicit Files(const std::string& name, bool half_inner = false, bool dry_lower_outer = false) {
    dir = tf::temp_dir(name);
    model = dir / "model.h5";
    flow = dir / "flow.h5";
    flaps = {tf::straight_flap("upper", {0.0, 0.1}, 0.1, 0.3, 9, 13),
             tf::straight_flap("lower", {0.0, -0.1}, -0.1, 0.3, 9, 13)};
    tf::write_model(model, flaps);
    std::vector<tf::TestTrace> traces;
    auto p = [](const Vec2& x) { return 2e5 - 3e5 * x.x(); };
    auto ambient = [](const Vec2&) { return 1e5; };
    auto tau = [](const Vec2& x) { return 50.0 * x.x(); };
    for (const auto& f : flaps) {
      // Flow traces twice as fine as the model walls, not matching the beam nodes.
      std::vector<Vec2> inner, outer;
      const std::size_t n = f.inner_wall.size();
      for (std::size_t i = 0; i + 1 < n; ++i) {
        for (double u : {0.0, 0.5}) {
          inner.push_back(f.inner_wall[i] + u * (f.inner_wall[i + 1] - f.inner_wall[i]));
          outer.push_back(f.outer_wall[i] + u * (f.outer_wall[i + 1] - f.outer_wall[i]));
        }
      }
      inner.push_back(f.inner_wall.back());
      outer.push_back(f.outer_wall.back());
      if (half_inner && f.name == "upper") inner.resize(inner.size() / 2);
      traces.push_back(tf::make_trace(f.name + "_in", f.name, "inner", inner, p, tau, -1.0));
      if (!(dry_lower_outer && f.name == "lower")) {
        traces.push_back(tf::make_trace(f.name + "_out", f.name, "outer", outer, ambient, tau, 1.0));
      }
    }
    // A wall that belongs to no flap is ignored.
    traces.push_back(tf::make_trace("duct", "", "", {{-0.2, 0.2}, {-0.1, 0.2}}, ambient, tau, -1.0));
    tf::write_flow(flow, traces);
  }
};

int run_cli(const std::string& arguments, std::string* stderr_text = nullptr) {
  const std::string err = (tf::process_temp_root() / "loads-stderr.txt").string();
  const int status = std::system((std::string(TFMB_BIN_DIR) + "/tfmb-loads " + arguments + " 2>" + err + " >/dev/null").c_str());
  if (stderr_text) {
    std::ifstream in(err);
    std::stringstream s;
    s << in.rdbuf();
    *stderr_text = s.str();
  }
  return WEXITSTATUS(status);
}

}  // namespace

TEST(LoadsFiles, ForcesWritesAValidFileAndPrintsTotals) {
  const Files files("forces");
  ASSERT_TRUE(problems(files.flow, "flow").empty()) << problems(files.flow, "flow").front();
  ASSERT_TRUE(problems(files.model, "model").empty()) << problems(files.model, "model").front();
  for (Method method : {Method::linear, Method::conservative}) {
    ForcesOptions o;
    o.flow_file = files.flow;
    o.model_file = files.model;
    o.output = files.dir / "loads.h5";
    o.method = method;
    std::ostringstream out;
    const ForcesResult r = run_forces(o, quiet, out);
    const auto p = problems(o.output, "loads");
    EXPECT_TRUE(p.empty()) << p.front();
    ASSERT_EQ(r.loads.flaps.size(), 2u);
    EXPECT_NE(out.str().find("upper"), std::string::npos);
    for (const auto& f : r.loads.flaps) {
      // Linear field on straight flaps: both methods keep the totals.
      EXPECT_LT((f.loads.mapped.force - f.loads.traces.force).norm(), 1e-10 * f.loads.traces.force.norm());
      // Net (p_in - p_out) > 0 pushes each flap from its inner towards its outer wall (the
      // left normal of the test flaps).
      const double angle = f.name == "upper" ? 0.1 : -0.1;
      EXPECT_GT(f.loads.traces.force.dot(Vec2(-std::sin(angle), std::cos(angle))), 0.0);
    }
    const h5::Reader reader(o.output);
    EXPECT_EQ(reader.attr_string("/", "method"), method_name(method));
  }
}

TEST(LoadsFiles, FunctionAndDiffNeedNoFlowFile) {
  const Files files("function");
  ForcesOptions o;
  o.model_file = files.model;
  o.output = files.dir / "loads.h5";
  o.function = "p_inner = 2e5 - 3e5*x; p_outer = 1e5; tau = 50*x";
  o.diff = true;
  std::ostringstream out;
  const ForcesResult r = run_forces(o, quiet, out);
  ASSERT_EQ(r.diffs.size(), 2u);
  for (const auto& d : r.diffs) {
    EXPECT_LT(d.max_distributed_force_error, 1e-9 * d.max_distributed_force);
    EXPECT_LT(d.force_error, 1e-10);
    EXPECT_LT(d.moment_error, 1e-10);
  }
  EXPECT_NE(out.str().find("mapping error"), std::string::npos);
}

TEST(LoadsFiles, TracesThatDoNotCoverAFlapAreRefused) {
  const Files files("uncovered", true);
  ForcesOptions o;
  o.flow_file = files.flow;
  o.model_file = files.model;
  o.output = files.dir / "loads.h5";
  try {
    std::ostringstream out;
    run_forces(o, quiet, out);
    FAIL() << "expected BadInput";
  } catch (const BadInput& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(files.flow.string()), std::string::npos) << m;
    EXPECT_NE(m.find("upper_in"), std::string::npos) << m;
    EXPECT_NE(m.find("uncovered"), std::string::npos) << m;
  }
  EXPECT_FALSE(std::filesystem::exists(o.output));
  std::string err;
  EXPECT_EQ(run_cli("forces " + files.flow.string() + " " + files.model.string() + " -o " +
                    (files.dir / "cli.h5").string(), &err), 3);
  EXPECT_NE(err.find("uncovered"), std::string::npos) << err;
}

TEST(LoadsFiles, DisplaceMapsARigidMotionAndRefusesAMismatchedStructure) {
  const Files files("displace");
  const double phi = 0.02;
  const Vec2 shift(0.001, 0.002), pivot(0.0, 0.0);
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(phi).toRotationMatrix();
  std::vector<tf::TestStructureFlap> sflaps;
  for (const auto& f : files.flaps) {
    tf::TestStructureFlap s;
    s.name = f.name;
    s.points = f.reference_curve;
    for (const Vec2& x : s.points) {
      s.displacement.push_back(shift + (R - Eigen::Matrix2d::Identity()) * (x - pivot));
      s.rotation_angle.push_back(phi);
    }
    sflaps.push_back(s);
  }
  const auto structure = files.dir / "structure.h5";
  tf::write_structure(structure, sflaps);
  DisplaceOptions o;
  o.structure_file = structure;
  o.model_file = files.model;
  o.mesh_file = files.flow;
  o.output = files.dir / "walldisp.h5";
  std::ostringstream out;
  const DisplaceResult r = run_displace(o, quiet, out);
  const auto p = problems(o.output, "walldisp");
  EXPECT_TRUE(p.empty()) << p.front();
  ASSERT_EQ(r.walls.size(), 4u);  // the duct wall has no flap
  for (const auto& w : r.walls) {
    for (std::size_t k = 0; k < w.points.size(); ++k) {
      const Vec2 exact = shift + (R - Eigen::Matrix2d::Identity()) * (w.points[k] - pivot);
      EXPECT_LT((w.displacement[k] - exact).norm(), 1e-15) << w.name << " " << k;
    }
  }
  // --function with --diff: the same rigid motion as an analytic field.
  DisplaceOptions f = o;
  f.structure_file.clear();
  f.function = "ux = 0.001 + (cos(0.02)-1)*x - sin(0.02)*y; uy = 0.002 + sin(0.02)*x + (cos(0.02)-1)*y; rz = 0.02";
  f.diff = true;
  const DisplaceResult rf = run_displace(f, quiet, out);
  for (double e : rf.max_error) EXPECT_LT(e, 1e-15);

  // A structure computed for another geometry: shifted beam nodes.
  for (auto& s : sflaps) for (auto& x : s.points) x.y() += 0.01;
  const auto shifted = files.dir / "shifted.h5";
  tf::write_structure(shifted, sflaps);
  std::string err;
  EXPECT_EQ(run_cli("displace " + shifted.string() + " " + files.model.string() + " -o " +
                    (files.dir / "bad.h5").string(), &err), 3);
  EXPECT_NE(err.find("/flaps/lower/nodes"), std::string::npos) << err;
  EXPECT_NE(err.find("mismatched model and structure"), std::string::npos) << err;
  // A structure with a flap the model does not have.
  sflaps.resize(1);
  sflaps[0].name = "other";
  tf::write_structure(shifted, sflaps);
  EXPECT_EQ(run_cli("displace " + shifted.string() + " " + files.model.string() + " -o " +
                    (files.dir / "bad.h5").string(), &err), 3);
  EXPECT_NE(err.find("/flaps/other"), std::string::npos) << err;
}

TEST(LoadsFiles, AFlapSideWithoutTracesIsRefusedUnlessGivenAPressure) {
  const Files files("dry", false, true);
  ForcesOptions o;
  o.flow_file = files.flow;
  o.model_file = files.model;
  o.output = files.dir / "loads.h5";
  std::ostringstream out;
  try {
    run_forces(o, quiet, out);
    FAIL() << "expected BadInput";
  } catch (const BadInput& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("flap 'lower' has no outer trace"), std::string::npos) << m;
    EXPECT_NE(m.find("--missing-side-pressure"), std::string::npos) << m;
  }
  // With the ambient pressure on the dry side the loads equal those of the wetted case, whose
  // outer trace carried the same uniform 1e5 Pa (its shear aside).
  o.missing_side_pressure = 1e5;
  const ForcesResult dry = run_forces(o, quiet, out);
  const Files wet_files("wet");
  o.flow_file = wet_files.flow;
  o.missing_side_pressure.reset();
  const ForcesResult wet = run_forces(o, quiet, out);
  const auto& d = dry.loads.flaps[0].loads;  // "lower" sorts first
  const auto& w = wet.loads.flaps[0].loads;
  ASSERT_EQ(dry.loads.flaps[0].name, "lower");
  // Shear of the wet outer trace: 50 x tau along the flap, w int 50 x ds.
  const double shear = 0.5 * 50.0 * 0.3 * 0.3 / 2.0 * std::cos(0.1);
  // (the 2 mm offset of the outer wall shifts x by up to 2e-4 m: 2e-3 N at most)
  EXPECT_NEAR((d.traces.force - w.traces.force).norm(), shear, 3e-3);
}

TEST(LoadsFiles, ATraceFarFromItsFlapIsRefused) {
  const Files files("stray");
  // The upper flap's walls again, labelled as the lower flap's end face.
  std::vector<tf::TestTrace> traces;
  auto p = [](const Vec2&) { return 1e5; };
  for (const auto& f : files.flaps) {
    traces.push_back(tf::make_trace(f.name + "_in", f.name, "inner", f.inner_wall, p, p, -1.0));
    traces.push_back(tf::make_trace(f.name + "_out", f.name, "outer", f.outer_wall, p, p, 1.0));
  }
  traces.push_back(tf::make_trace("stray", "lower", "end", files.flaps[0].outer_wall, p, p, 1.0));
  tf::write_flow(files.flow, traces);
  std::string err;
  EXPECT_EQ(run_cli("forces " + files.flow.string() + " " + files.model.string() + " -o " +
                    (files.dir / "loads.h5").string(), &err), 3);
  EXPECT_NE(err.find("/walls/stray: point 0 lies"), std::string::npos) << err;
  EXPECT_NE(err.find("flap attribute"), std::string::npos) << err;
}

// The fluid side of a wall comes from the flow file's normals (flow 1.4): the same traces with
// their normals reversed load the flap from the other side. The normals are optional: without
// them the side comes from the mesh's cells along the wall, with the same loads.
TEST(LoadsFiles, TheWallNormalsSayWhereTheFluidIs) {
  auto total_y = [](const std::string& name, double fluid_side) {
    const Files files(name);
    const tf::TestFlap& flap = files.flaps[0];
    auto p = [](const Vec2&) { return 2e5; };
    auto ambient = [](const Vec2&) { return 1e5; };  // wall pressures are absolute: positive
    auto zero = [](const Vec2&) { return 0.0; };
    tf::write_flow(
        files.flow,
        {tf::make_trace("in", flap.name, "inner", flap.inner_wall, p, zero, fluid_side),
         tf::make_trace("out", flap.name, "outer", flap.outer_wall, ambient, zero, -fluid_side),
         tf::make_trace("lower_in", "lower", "inner", files.flaps[1].inner_wall, ambient, zero,
                        1.0),
         tf::make_trace("lower_out", "lower", "outer", files.flaps[1].outer_wall, ambient, zero,
                        -1.0)});
    const auto out = files.dir / "loads.h5";
    EXPECT_EQ(run_cli("forces " + files.flow.string() + " " + files.model.string() + " -o " +
                      out.string()),
              0);
    const h5::Reader r(out);
    const h5::MatrixXdR f = r.read_matrix("/flaps/" + flap.name + "/nodal_force", std::nullopt, 3);
    return f.col(1).sum();
  };
  const double as_given = total_y("normals-right", -1.0),
               reversed = total_y("normals-reversed", 1.0);
  EXPECT_GT(std::abs(as_given), 1e3);
  EXPECT_NEAR(reversed, -as_given, 1e-9 * std::abs(as_given));

  // The same flow as "normals-right" without any wall normals: the same loads, from the mesh.
  auto drop_normals = [](const std::filesystem::path& flow) {
    const hid_t file = H5Fopen(flow.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    for (const char* wall : {"in", "out", "lower_in", "lower_out"}) {
      EXPECT_GE(H5Ldelete(file, (std::string("/walls/") + wall + "/normal").c_str(), H5P_DEFAULT),
                0);
    }
    H5Fclose(file);
  };
  {
    const Files files("normals-missing");
    const tf::TestFlap& flap = files.flaps[0];
    auto p = [](const Vec2&) { return 2e5; };
    auto ambient = [](const Vec2&) { return 1e5; };
    auto zero = [](const Vec2&) { return 0.0; };
    tf::write_flow(files.flow,
                   {tf::make_trace("in", flap.name, "inner", flap.inner_wall, p, zero, -1.0),
                    tf::make_trace("out", flap.name, "outer", flap.outer_wall, ambient, zero, 1.0),
                    tf::make_trace("lower_in", "lower", "inner", files.flaps[1].inner_wall, ambient,
                                   zero, 1.0),
                    tf::make_trace("lower_out", "lower", "outer", files.flaps[1].outer_wall,
                                   ambient, zero, -1.0)});
    drop_normals(files.flow);
    const auto out = files.dir / "loads.h5";
    ASSERT_EQ(run_cli("forces " + files.flow.string() + " " + files.model.string() + " -o " +
                      out.string()),
              0);
    const h5::Reader r(out);
    const h5::MatrixXdR f = r.read_matrix("/flaps/" + flap.name + "/nodal_force", std::nullopt, 3);
    EXPECT_NEAR(f.col(1).sum(), as_given, 1e-9 * std::abs(as_given));
  }
}
