// tfmb-heat-bench: steady nonlinear conduction on a long thin strip of linear quads (about 200k
// nodes by default), printing wall time, Newton iterations and peak memory (VmHWM). With
// --calculix (and ccx on PATH) the same mesh and boundary data are written as a CalculiX heat
// transfer deck, ccx is run, and the largest temperature difference and both wall times are
// printed. A benchmark, not a test: nothing is asserted.
//
// Sample runs:
//   tfmb-heat-bench                               # 20000 x 10 cells, 220011 nodes
//   tfmb-heat-bench --calculix                    # plus the CalculiX side by side
//   tfmb-heat-bench --cells-along 2000 --calculix # smaller strip
//
// Case (illustrative data, not a nozzle result): strip 1 m x 10 mm, titanium-like k(T) table;
// inner face convection with h(s) = 600..1000 W/(m^2 K), T_aw(s) = 1400..1000 K; outer face
// convection 20 W/(m^2 K) to 300 K plus radiation (emissivity 0.8, 300 K); end x = 0 held at
// 600 K; end x = 1 m adiabatic.
#include "tfmb-heat/calculix_export.hpp"
#include "tfmb-heat/steady_solver.hpp"
#include "tfmb-heat/strip_mesh.hpp"

#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include <unistd.h>

using namespace tfmb::heat;

namespace {

long peak_memory_kib() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::strtol(line.c_str() + 6, nullptr, 10);
  }
  return -1;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Trace sampled(double length, int count, double (*f)(double), const char* name) {
  std::vector<double> s, v;
  for (int i = 0; i < count; ++i) {
    s.push_back(length * i / (count - 1));
    v.push_back(f(s.back()));
  }
  return Trace(s, v, name);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"tfmb-heat benchmark: steady nonlinear conduction on a long strip of quads"};
  int cells_along = 20000, cells_through = 10;
  bool calculix = false, picard = false;
  std::string keep_dir;
  app.add_option("--cells-along", cells_along, "cells along the 1 m strip")->check(CLI::PositiveNumber);
  app.add_option("--cells-through", cells_through, "cells through the 10 mm thickness")->check(CLI::PositiveNumber);
  app.add_flag("--calculix", calculix, "also run CalculiX (ccx) on the same mesh and data");
  app.add_flag("--picard", picard, "Picard tangent with SimplicialLDLT instead of Newton with SparseLU");
  app.add_option("--keep", keep_dir, "directory for the CalculiX deck and output (default: a temporary one)");
  CLI11_PARSE(app, argc, argv);

  const auto start = std::chrono::steady_clock::now();
  StripMeshOptions o;
  o.length = 1.0;
  o.thickness = 0.01;
  o.cells_along = cells_along;
  o.cells_through = cells_through;
  const SolidMesh mesh = make_strip_mesh(o);
  ThermalProblem problem;
  problem.mesh = &mesh;
  problem.materials = {{"titanium-like (illustrative)",
                        PropertyTable({250, 500, 750, 1000, 1500}, {6.0, 8.5, 11.5, 15.0, 22.0}),
                        {}, {}}};
  problem.boundary_conditions = {
      {"bottom", Convection{sampled(1.0, 101, [](double s) { return 800.0 + 200.0 * std::cos(std::numbers::pi * s); }, "h"),
                            sampled(1.0, 101, [](double s) { return 1400.0 - 400.0 * s; }, "T_aw")}},
      {"top", Convection{Trace({0.0, 1.0}, {20.0, 20.0}, "h"), Trace({0.0, 1.0}, {300.0, 300.0}, "T_amb")}},
      {"top", Radiation{0.8, 300.0}},
      {"left", ImposedTemperature{Trace({0.0, 0.01}, {600.0, 600.0}, "T_joint")}}};
  const double mesh_seconds = seconds_since(start);

  NewtonSettings settings;
  settings.temperature_tolerance = 1e-6;
  if (picard) settings.tangent = Tangent::picard;
  const auto solve_start = std::chrono::steady_clock::now();
  const auto result = solve_steady(problem, 800.0, settings);
  const double solve_seconds = seconds_since(solve_start);
  std::printf("tfmb-heat: %zu nodes, %zu quads, %s\n", mesh.node_count(), mesh.cell_count(),
              picard ? "Picard + SimplicialLDLT" : "Newton (consistent tangent) + SparseLU");
  std::printf("tfmb-heat: %d iterations, converged %s, updates [K]:", result.newton.iterations,
              result.newton.converged ? "yes" : "NO");
  for (double u : result.newton.max_update) std::printf(" %.2e", u);
  std::printf("\ntfmb-heat: T range %.3f .. %.3f K\n", result.temperature.minCoeff(), result.temperature.maxCoeff());
  std::printf("tfmb-heat: mesh %.3f s, setup+solve %.3f s wall (assembly %.3f s, factorise+solve %.3f s), "
              "process CPU %.3f s, peak memory (VmHWM) %.1f MiB\n",
              mesh_seconds, solve_seconds, result.newton.assembly_seconds, result.newton.solve_seconds,
              static_cast<double>(std::clock()) / CLOCKS_PER_SEC, peak_memory_kib() / 1024.0);

  if (!calculix) return 0;
  if (std::system("command -v ccx > /dev/null 2>&1") != 0) {
    std::printf("calculix: ccx not on PATH, comparison skipped\n");
    return 0;
  }
  const std::filesystem::path dir = keep_dir.empty()
      ? std::filesystem::temp_directory_path() / ("tfmb-heat-bench-" + std::to_string(::getpid()))
      : std::filesystem::path(keep_dir);
  std::filesystem::create_directories(dir);
  {
    std::ofstream deck(dir / "strip.inp");
    write_calculix_input(deck, problem, 800.0);
  }
  const auto ccx_start = std::chrono::steady_clock::now();
  const std::string command = "cd '" + dir.string() + "' && OMP_NUM_THREADS=1 ccx -i strip > ccx.log 2>&1";
  const int status = std::system(command.c_str());
  const double ccx_seconds = seconds_since(ccx_start);
  if (status != 0) {
    std::printf("calculix: ccx failed (status %d), see %s\n", status, (dir / "ccx.log").c_str());
    return 1;
  }
  const auto t_ccx = read_calculix_temperatures((dir / "strip.dat").string(), mesh.node_count());
  Eigen::Index worst = 0;
  const double difference = (result.temperature - t_ccx).cwiseAbs().maxCoeff(&worst);
  std::printf("calculix: T range %.3f .. %.3f K\n", t_ccx.minCoeff(), t_ccx.maxCoeff());
  std::printf("side by side: max |T_tfmb - T_ccx| = %.4f K at (%.4f, %.4f) m (T_tfmb %.3f K); "
              "wall time tfmb-heat %.3f s, ccx %.3f s\n",
              difference, mesh.points(worst, 0), mesh.points(worst, 1), result.temperature[worst],
              solve_seconds, ccx_seconds);
  if (keep_dir.empty()) std::filesystem::remove_all(dir);
  return 0;
}
