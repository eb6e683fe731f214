// Benchmark (not a test): builds a flow mesh of about 100k nodes for the simple-nozzle case and
// prints node count, wall and CPU time (the machine is shared: CPU time is the steadier figure). Usage: bench_flow_mesh [scale] [algorithm]
#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <sstream>

#include "tfmb-input/case_file.hpp"
#include "tfmb-mesh/mesh_tools.hpp"
#include "tfmb-input/model_build.hpp"

int main(int argc, char** argv) {
  using namespace tfmb;
  const double scale = argc > 1 ? std::atof(argv[1]) : 0.66;
  const int algorithm = argc > 2 ? std::atoi(argv[2]) : 6;
  const auto spec = input::read_case(std::string(TFMB_SOURCE_DIR) + "/cases/simple-nozzle/case.toml", {});
  const auto curves = input::read_geometry(spec.geometry.file, spec.geometry.scale, spec.geometry.curve_samples);
  std::ostringstream sink;
  const Logger quiet("bench", Verbosity::quiet, sink);
  const auto model = input::build_model(spec, curves, quiet);
  mesh::FlowMeshOptions options;
  options.scale = scale;
  options.algorithm = algorithm;
  mesh::FlowMeshReport report;
  Stopwatch clock;
  const std::clock_t cpu_start = std::clock();
  const auto m = mesh::build_flow_mesh(model, options, report, quiet);
  std::printf("simple-nozzle flow mesh, scale %.3g, gmsh algorithm %d: %zu nodes, %lld triangles, %lld quads, "
              "%.2f s wall, %.2f s CPU (min angle %.1f deg)\n",
              scale, algorithm, m.node_count(), static_cast<long long>(m.triangles.rows()),
              static_cast<long long>(m.quads.rows()), clock.seconds(),
              static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC, report.quality.min_angle);
  return 0;
}
