// NASA TMR zero-pressure-gradient flat plate (cases/tmr-flatplate): the case chain tfmb-input ->
// tfmb-mesh -> tfmb-flow on the 137 x 97-point grid level, Cf at x = 0.97008 and the friction
// drag against FUN3D and CFL3D on the same level: Spalart-Allmaras against
// refdata/flow/tmr_flatplate_sa_cf_x097_convergence.csv and ..._cd_convergence.csv, k-omega
// SST-V against tmr_flatplate_sstv_*. Tolerance 1 % of FUN3D (issue 5) for Cf; our streamwise
// clustering is not TMR's (see the case README), so the two codes' spread on this level (SA: 0.3
// % for Cf; SST-V: 0.2 % for Cf, 1.9 % for CD) is the scale of what to expect.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "tfmb/common/h5.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path source_dir = TFMB_SOURCE_DIR;
const fs::path bin_dir = TFMB_BIN_DIR;

int run(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// value of `column` for `code`, grid "137x97", quadrilateral grid
double reference(const std::string& file, const std::string& code) {
  std::ifstream in(source_dir / "refdata/flow" / file);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::stringstream s(line);
    std::vector<std::string> cells;
    std::string cell;
    while (std::getline(s, cell, ',')) cells.push_back(cell);
    if (cells.size() == 6 && cells[0] == code && cells[1].rfind("quadrilateral", 0) == 0 && cells[2] == "137x97") {
      return std::stod(cells[5]);
    }
  }
  return std::nan("");
}

}  // namespace

namespace {

// The case chain with `model` on the 137 x 97 level, checked against the reference files
// refdata/flow/tmr_flatplate_<reference>_*; `cd_tolerance` relative to FUN3D.
void check_flat_plate(const std::string& model, const std::string& reference_name, double cd_tolerance) {
  for (const char* tool : {"tfmb-input", "tfmb-mesh", "tfmb-flow"}) {
    if (!fs::exists(bin_dir / tool)) GTEST_SKIP() << tool << " not built";
  }
  const fs::path dir = fs::temp_directory_path() / ("tfmb_tmr_" + model + "_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string quiet = " -q 2>>" + (dir / "log.txt").string();
  ASSERT_EQ(run((bin_dir / "tfmb-input").string() + " " + (source_dir / "cases/tmr-flatplate/case.toml").string() +
                " -o " + (dir / "model.h5").string() + quiet), 0);
  ASSERT_EQ(run((bin_dir / "tfmb-mesh").string() + " flow " + (dir / "model.h5").string() + " -o " +
                (dir / "flowmesh.h5").string() + " 2>>" + (dir / "log.txt").string()), 0);
  // conditions of case.toml (flow-args would print the same)
  ASSERT_EQ(run((bin_dir / "tfmb-flow").string() + " " + (dir / "flowmesh.h5").string() +
                " --p0 117686.646 --T0 302.4 --ambient-pressure 114450 --ambient-temperature 300"
                " --freestream-mach 0.2 --model " + model + " --threads 1 --max-iterations 400 -o " +
                (dir / "flow.h5").string() + quiet), 0);
  const tfmb::h5::Reader flow(dir / "flow.h5");
  const auto x = flow.read_vector("/walls/plate/x");
  const auto tau = flow.read_vector("/walls/plate/wall_shear");
  const double p_inf = 1.1445e5, t_inf = 300.0, r_gas = 287.05;
  const double rho = p_inf / (r_gas * t_inf), u = 0.2 * std::sqrt(1.4 * r_gas * t_inf);
  const double q = 0.5 * rho * u * u;
  // Cf at x = 0.97008 (linear between trace points) and drag over the plate (reference length 2)
  const double x_ref = 0.970084071;
  double cf = std::nan(""), drag = 0.0;
  for (std::size_t k = 1; k < x.size(); ++k) {
    const double a = std::min(x[k - 1], x[k]), b = std::max(x[k - 1], x[k]);
    drag += 0.5 * (std::abs(tau[k - 1]) + std::abs(tau[k])) * (b - a);
    if (x_ref >= a && x_ref <= b) {
      const double f = (x_ref - x[k - 1]) / (x[k] - x[k - 1]);
      cf = std::abs((1.0 - f) * tau[k - 1] + f * tau[k]) / q;
    }
  }
  const double cd = drag / (q * 2.0);
  const std::string cf_file = "tmr_flatplate_" + reference_name + "_cf_x097_convergence.csv";
  const std::string cd_file = "tmr_flatplate_" + reference_name + "_cd_convergence.csv";
  const double cf_fun3d = reference(cf_file, "FUN3D");
  const double cf_cfl3d = reference(cf_file, "CFL3D");
  const double cd_fun3d = reference(cd_file, "FUN3D");
  const double cd_cfl3d = reference(cd_file, "CFL3D");
  ASSERT_TRUE(std::isfinite(cf_fun3d) && std::isfinite(cd_fun3d)) << "refdata rows for 137x97 not found";
  std::printf("TMR flat plate 137x97, %s: Cf(0.97) %.5e (FUN3D %.5e: %+.2f %%, CFL3D %.5e: %+.2f %%)\n", model.c_str(), cf, cf_fun3d,
              100.0 * (cf / cf_fun3d - 1.0), cf_cfl3d, 100.0 * (cf / cf_cfl3d - 1.0));
  std::printf("                         CD %.5e (FUN3D %.5e: %+.2f %%, CFL3D %.5e: %+.2f %%)\n", cd, cd_fun3d,
              100.0 * (cd / cd_fun3d - 1.0), cd_cfl3d, 100.0 * (cd / cd_cfl3d - 1.0));
  EXPECT_NEAR(cf / cf_fun3d, 1.0, 0.01);
  EXPECT_NEAR(cd / cd_fun3d, 1.0, cd_tolerance);
  EXPECT_EQ(flow.attr_i64("/convergence", "converged"), 1);

  // Heat transfer (the isothermal probe run): the adiabatic wall temperature against the
  // turbulent recovery factor Pr^(1/3), and h against the Colburn-Reynolds analogy
  // St = Cf/2 Pr^(-2/3) with the local Cf (Colburn's analogy, Incropera et al. 2007, sec. 7.2;
  // the recovery factor, White 2006, ch. 7); the analogy itself holds to a few per cent here.
  const auto t_aw = flow.read_vector("/walls/plate/adiabatic_wall_temperature");
  const auto h = flow.read_vector("/walls/plate/heat_transfer_coefficient");
  const double pr = 0.72, cp = 1.4 * r_gas / 0.4;
  const double t_recovery = t_inf + std::cbrt(pr) * (u * u / (2.0 * cp));
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (x[k] < 0.3 || x[k] > 1.8) continue;
    EXPECT_NEAR(t_aw[k], t_recovery, 0.1) << "x " << x[k];
    const double colburn = 0.5 * std::abs(tau[k]) / q * std::pow(pr, -2.0 / 3.0) * rho * u * cp;
    EXPECT_NEAR(h[k] / colburn, 1.0, 0.1) << "x " << x[k];
    if (std::abs(x[k] - x_ref) < 0.01) {
      std::printf("  x %.3f: T_aw %.3f K (recovery Pr^1/3: %.3f K), h %.1f W/(m^2 K) (Colburn %.1f)\n", x[k], t_aw[k],
                  t_recovery, h[k], colburn);
    }
  }
  fs::remove_all(dir);
}

// model.h5 and flowmesh.h5 of the 69 x 49-point level in `dir` (log.txt there), with `extra`
// --set options; false if a tool failed
bool make_level_69(const fs::path& dir, const std::string& extra) {
  const std::string log = " 2>>" + (dir / "log.txt").string();
  return run((bin_dir / "tfmb-input").string() + " " +
             (source_dir / "cases/tmr-flatplate/case.toml").string() +
             " --set mesh.cells_upstream=12 --set mesh.cells_along=56 --set mesh.cells_across=48"
             " --set flow.first_cell_height=4e-6" +
             extra + " -o " + (dir / "model.h5").string() + " -q" + log) == 0 &&
         run((bin_dir / "tfmb-mesh").string() + " flow " + (dir / "model.h5").string() + " -o " +
             (dir / "flowmesh.h5").string() + log) == 0;
}

}  // namespace

TEST(TmrFlatPlate, SpalartAllmarasSkinFrictionAndDrag) { check_flat_plate("sa", "sa", 0.01); }

// SST-V, the form of TMR's CFL3D and FUN3D SST results. CD to 2 %: on this level the two
// reference codes themselves differ by 1.9 % (2.8260e-3 and 2.7733e-3), FUN3D the lower.
TEST(TmrFlatPlate, SstSkinFrictionAndDrag) { check_flat_plate("sst-v", "sstv", 0.02); }

// The coupled Newton step (mean flow and nu_tilde in one 5x5 block system, matrix-free, so the
// Krylov operator carries the cross terms) drives the same residual to zero as the segregated
// step: the converged solutions must agree to the convergence level whatever path each took.
// On the 69 x 49 level, second order with the limiter made inactive (a Wang epsilon of 100
// times each variable's range): a limiter frozen at different iterates by the two paths would
// otherwise give two slightly different discrete schemes (measured: 2e-3 of the wall shear on
// 137 x 97). A wrong nu_tilde residual or update (e.g. no step limit on nu_tilde, which once
// froze the limiter in a transient) gave 0.25.
TEST(TmrFlatPlate, CoupledSpalartAllmarasGivesTheSegregatedSolution) {
  for (const char* tool : {"tfmb-input", "tfmb-mesh", "tfmb-flow"}) {
    if (!fs::exists(bin_dir / tool))
      GTEST_SKIP() << tool << " not built";
  }
  const fs::path dir =
      fs::temp_directory_path() / ("tfmb_tmr_coupled_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string quiet = " -q 2>>" + (dir / "log.txt").string();
  ASSERT_TRUE(make_level_69(dir, ""));
  const std::string common =
      (bin_dir / "tfmb-flow").string() + " " + (dir / "flowmesh.h5").string() +
      " --p0 117686.646 --T0 302.4 --ambient-pressure 114450 --ambient-temperature 300"
      " --freestream-mach 0.2 --model sa --threads 1 --max-iterations 400"
      " --heat-transfer-dt 0 --limiter-coefficient 100";
  ASSERT_EQ(run(common + " --turbulence-coupling segregated -o " +
                (dir / "segregated.h5").string() + quiet),
            0);
  ASSERT_EQ(run(common + " --matrix-free true --turbulence-coupling coupled -o " +
                (dir / "coupled.h5").string() + quiet),
            0);
  const tfmb::h5::Reader segregated(dir / "segregated.h5");
  const tfmb::h5::Reader coupled(dir / "coupled.h5");
  EXPECT_EQ(coupled.attr_i64("/convergence", "converged"), 1);
  const auto x = coupled.read_vector("/walls/plate/x");
  const auto tau_s = segregated.read_vector("/walls/plate/wall_shear");
  const auto tau_c = coupled.read_vector("/walls/plate/wall_shear");
  const auto nu_s = segregated.read_vector("/fields/point/nu_tilde");
  const auto nu_c = coupled.read_vector("/fields/point/nu_tilde");
  ASSERT_EQ(tau_s.size(), tau_c.size());
  ASSERT_EQ(nu_s.size(), nu_c.size());
  double tau_max = 0.0, tau_diff = 0.0, nu_max = 0.0, nu_diff = 0.0;
  for (std::size_t k = 0; k < tau_s.size(); ++k) {
    if (x[k] < 0.05)
      continue;  // the leading-edge singularity
    tau_max = std::max(tau_max, std::abs(tau_s[k]));
    tau_diff = std::max(tau_diff, std::abs(tau_c[k] - tau_s[k]));
  }
  for (std::size_t k = 0; k < nu_s.size(); ++k) {
    nu_max = std::max(nu_max, std::abs(nu_s[k]));
    nu_diff = std::max(nu_diff, std::abs(nu_c[k] - nu_s[k]));
  }
  const auto its = [](const tfmb::h5::Reader& f) {
    return f.attr_i64("/convergence", "iterations");
  };
  std::printf(
      "TMR flat plate 69x49, SA: segregated %lld iterations, coupled matrix-free %lld; "
      "largest difference of wall shear %.2e, of nu_tilde %.2e (relative to the largest)\n",
      static_cast<long long>(its(segregated)), static_cast<long long>(its(coupled)),
      tau_diff / tau_max, nu_diff / nu_max);
  EXPECT_LT(tau_diff / tau_max, 1e-5);
  EXPECT_LT(nu_diff / nu_max, 1e-5);
  fs::remove_all(dir);
}

// The time-accurate mode with k-omega SST: a converged steady SST-V state (69 x 49 level, 8
// orders) restarted with physical time steps must stay where it is, k and omega included. A wrong
// sign or a wrong time level in k's or omega's time derivative moves it by orders of magnitude
// (measured with k's sign flipped: wall shear changed by 117 %, k by a factor 1e4; as written:
// 4e-7 and 2e-6).
TEST(TmrFlatPlate, SstTimeAccurateKeepsTheSteadyState) {
  for (const char* tool : {"tfmb-input", "tfmb-mesh", "tfmb-flow"}) {
    if (!fs::exists(bin_dir / tool))
      GTEST_SKIP() << tool << " not built";
  }
  const fs::path dir =
      fs::temp_directory_path() / ("tfmb_tmr_sst_time_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string quiet = " -q 2>>" + (dir / "log.txt").string();
  ASSERT_TRUE(make_level_69(dir, " --set mesh.leading_edge_spacing=0.004"));
  const std::string common =
      (bin_dir / "tfmb-flow").string() + " " + (dir / "flowmesh.h5").string() +
      " --p0 117686.646 --T0 302.4 --ambient-pressure 114450 --ambient-temperature 300"
      " --freestream-mach 0.2 --model sst-v --threads 1 --heat-transfer-dt 0";
  ASSERT_EQ(run(common + " --max-iterations 1500 -o " + (dir / "steady.h5").string() + quiet), 0);
  ASSERT_EQ(run(common + " --restart " + (dir / "steady.h5").string() +
                " --time-step 1e-4 --time-steps 10 --statistics-start 1 -o " +
                (dir / "mean.h5").string() + quiet),
            0);
  const tfmb::h5::Reader steady(dir / "steady.h5"), mean(dir / "mean.h5");
  EXPECT_EQ(mean.attr_i64("/convergence", "time_average"), 1);
  auto largest_change = [&](const std::string& path) {
    const auto a = steady.read_vector(path), b = mean.read_vector(path);
    double diff = 0.0, scale = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) {
      diff = std::max(diff, std::abs(a[k] - b[k]));
      scale = std::max(scale, std::abs(a[k]));
    }
    return diff / scale;
  };
  const double shear = largest_change("/walls/plate/wall_shear");
  const double k = largest_change("/fields/point/turbulent_kinetic_energy");
  const double omega = largest_change("/fields/point/specific_dissipation_rate");
  std::printf(
      "SST-V steady state under 10 time steps: largest change of wall shear %.2e, k %.2e, omega "
      "%.2e\n",
      shear, k, omega);
  EXPECT_LT(shear, 1e-5);
  EXPECT_LT(k, 1e-4);
  EXPECT_LT(omega, 1e-4);
  fs::remove_all(dir);
}
