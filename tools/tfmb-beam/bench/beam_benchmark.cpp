// tfmb-beam-benchmark: the 45-degree bend (Bathe & Bolourchi 1979) at P = 600 with 16 elements,
// timed against CalculiX (16 x B32R, NLGEOM) when `ccx` is on PATH, plus the time of a
// 1000-element nonlinear static solve. Prints figures; asserts nothing.
//
// Sample runs:
//   build/bin/tfmb-beam-benchmark
//   build/bin/tfmb-beam-benchmark --ccx-input refdata/beam/calculix/bend45_16el.inp
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>
#include <string>

#include "tfmb-beam/assembly.hpp"
#include "tfmb-beam/cases.hpp"
#include "tfmb-beam/static_solver.hpp"

using namespace tfmb::beam;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

struct Run {
  double seconds = 0.0;
  Eigen::Vector3d tip = Eigen::Vector3d::Zero();
  int steps = 0, iterations = 0;
  bool converged = false;
};

Run run_bend45(int n_elements, int repeats) {
  Run best;
  best.seconds = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = Clock::now();
    Model m = cases::bend45(n_elements, 600.0, 1.0, 1.0 / 6.0);
    Assembly asmb(m);
    StaticOptions opt;
    opt.initial_steps = 4;
    const StaticResult res = solve_static(asmb, asmb.initial_state(), opt);
    const double s = seconds_since(t0);
    if (s < best.seconds) {
      best.seconds = s;
      best.tip = res.state.position.back();
      best.steps = res.steps;
      best.iterations = res.iterations;
      best.converged = res.converged;
    }
  }
  return best;
}

bool on_path(const std::string& exe) {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::stringstream ss(path);
  std::string dir;
  while (std::getline(ss, dir, ':'))
    if (!dir.empty() && std::filesystem::exists(std::filesystem::path(dir) / exe)) return true;
  return false;
}

/// Runs ccx on a copy of `input` in a temporary directory; returns wall time and the last tip
/// displacement printed in the .dat file.
bool run_calculix(const std::string& input, double& seconds, Eigen::Vector3d& displacement) {
  const auto dir = std::filesystem::temp_directory_path() / ("tfmb-beam-bench-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(input, dir / "bend.inp", std::filesystem::copy_options::overwrite_existing);
  const std::string cmd = "cd '" + dir.string() + "' && OMP_NUM_THREADS=1 ccx bend > ccx.log 2>&1";
  const auto t0 = Clock::now();
  const int rc = std::system(cmd.c_str());
  seconds = seconds_since(t0);
  bool found = false;
  std::ifstream dat(dir / "bend.dat");
  std::string line;
  const std::regex row(R"(^\s*\d+\s+([-+0-9.Ee]+)\s+([-+0-9.Ee]+)\s+([-+0-9.Ee]+)\s*$)");
  std::smatch mt;
  while (std::getline(dat, line))
    if (std::regex_match(line, mt, row)) {
      displacement = Eigen::Vector3d(std::stod(mt[1]), std::stod(mt[2]), std::stod(mt[3]));
      found = true;
    }
  std::filesystem::remove_all(dir);
  return rc == 0 && found;
}

}  // namespace

int main(int argc, char** argv) {
  std::string ccx_input = "refdata/beam/calculix/bend45_16el.inp";
  int big = 1000;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--ccx-input" && i + 1 < argc) ccx_input = argv[++i];
    else if (a == "--big" && i + 1 < argc) big = std::atoi(argv[++i]);
    else if (a == "--help") {
      std::cout << "usage: tfmb-beam-benchmark [--ccx-input FILE.inp] [--big N_ELEMENTS]\n";
      return 0;
    } else {
      std::cerr << "unknown option " << a << "\n";
      return 2;
    }
  }
  std::printf("45-degree bend, P = 600 (dead, +z), 16 quadratic elements, J = 1/6, k = 1\n");
  const Run ours = run_bend45(16, 5);
  std::printf("  tfmb-beam : %8.4f s (best of 5, model setup included), tip (%.4f, %.4f, %.4f), %d steps, %d Newton iterations%s\n",
              ours.seconds, ours.tip.x(), ours.tip.y(), ours.tip.z(), ours.steps, ours.iterations,
              ours.converged ? "" : "  NOT CONVERGED");
  if (on_path("ccx") && std::filesystem::exists(ccx_input)) {
    double s = 0.0;
    Eigen::Vector3d u = Eigen::Vector3d::Zero();
    if (run_calculix(ccx_input, s, u)) {
      const Eigen::Vector3d tip0(100.0 - 100.0 / std::sqrt(2.0), 100.0 / std::sqrt(2.0), 0.0);
      const Eigen::Vector3d tip = tip0 + u;
      std::printf("  CalculiX  : %8.4f s (wall, whole ccx run), tip (%.4f, %.4f, %.4f)  [%s]\n", s, tip.x(), tip.y(),
                  tip.z(), ccx_input.c_str());
      std::printf("  speed-up  : %.1f x; tip difference %.2e relative\n", s / ours.seconds,
                  (tip - ours.tip).norm() / tip.norm());
    } else {
      std::printf("  CalculiX  : run failed (%s)\n", ccx_input.c_str());
    }
  } else {
    std::printf("  CalculiX  : ccx not on PATH or input missing; skipped\n");
  }
  std::printf("%d-element nonlinear static solve (same bend, P = 600)\n", big);
  const Run large = run_bend45(big, 1);
  std::printf("  tfmb-beam : %8.4f s, tip (%.4f, %.4f, %.4f), %d steps, %d Newton iterations%s\n", large.seconds,
              large.tip.x(), large.tip.y(), large.tip.z(), large.steps, large.iterations,
              large.converged ? "" : "  NOT CONVERGED");
  return 0;
}
