// tfmb-beam-flexible-joint-seed: the two examples of the flexible-joint seed (Bauchau & Han), run
// with the beam library (both are 3D; the file stage of tfmb-beam is planar) and written as CSV.
//
// Sample run (Makefile.cases CASE=flexible-joint structure runs it):
//   tfmb-beam-flexible-joint-seed -o runs/flexible-joint
// writes example1.csv (both measures, handles k/l in both orders, a = 0 .. 9), example2.csv (the
// sixteen lambda/mu cases, a = 0 .. 9; also example2-rot1000.csv with rotational stiffness 1000
// about all axes), *-small-load.csv (example 2 at small a) and summary.json.
#include <CLI/CLI.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>

#include "tfmb-beam/assembly.hpp"
#include "tfmb-beam/cases.hpp"
#include "tfmb-beam/flexible_joint_seed.hpp"
#include "tfmb-beam/static_solver.hpp"

using namespace tfmb::beam;

int main(int argc, char** argv) {
  CLI::App app{"The flexible-joint seed's examples 1 and 2 -> CSV files and summary.json", "tfmb-beam-flexible-joint-seed"};
  std::filesystem::path out_dir;
  double step = 0.25;
  app.add_option("-o,--output", out_dir, "output folder")->required();
  app.add_option("--step", step, "load factor a step (a = 0 .. 9)")->capture_default_str()->check(CLI::Range(1e-3, 9.0));
  CLI11_PARSE(app, argc, argv);
  try {
    std::filesystem::create_directories(out_dir);
    std::vector<double> a_levels;
    for (int i = 1; i * step <= 9.0 + 1e-9; ++i) a_levels.push_back(i * step);

    // Example 1: both measures, both handle orders.
    std::ofstream e1(out_dir / "example1.csv");
    e1 << std::setprecision(12);
    e1 << "measure,handles,a,tip_u1,tip_u2,tip_u3,stretch_1,stretch_2,stretch_3,wryness_1,wryness_2,wryness_3\n";
    std::ofstream summary(out_dir / "summary.json");
    summary << std::setprecision(6) << "{\n  \"example1\": {";
    bool first = true;
    for (FlexibleMeasure measure : {FlexibleMeasure::proposed, FlexibleMeasure::typical}) {
      const char* name = measure == FlexibleMeasure::proposed ? "proposed" : "typical";
      const seed::Example1Result r = seed::run_example1(measure, a_levels);
      for (int order = 0; order < 2; ++order)
        for (size_t i = 0; i < r.a.size(); ++i) {
          const auto& p = order == 0 ? r.kl[i] : r.lk[i];
          e1 << name << ',' << (order == 0 ? "kl" : "lk") << ',' << r.a[i];
          for (int c = 0; c < 3; ++c) e1 << ',' << p.tip_displacement(c);
          for (int c = 0; c < 6; ++c) e1 << ',' << p.measures(c);
          e1 << '\n';
        }
      std::cerr << "example 1, " << name << " measures: reached a = " << (r.a.empty() ? 0.0 : r.a.back())
                << "; swapping k and l changes the nodal positions by " << r.max_position_difference
                << " and rotations by " << r.max_rotation_difference << " (relative to the largest displacement/rotation), the "
                << "joint measures by " << r.max_measure_difference << " (relative, E_kl vs -E_lk)\n";
      summary << (first ? "" : ",") << "\n    \"" << name << "\": {\"a_reached\": " << (r.a.empty() ? 0.0 : r.a.back())
              << ", \"swap_position_difference\": " << r.max_position_difference
              << ", \"swap_rotation_difference\": " << r.max_rotation_difference
              << ", \"swap_measure_difference\": " << r.max_measure_difference
              << ", \"tip_displacement_a9\": [" << r.kl.back().tip_displacement(0) << ", " << r.kl.back().tip_displacement(1)
              << ", " << r.kl.back().tip_displacement(2) << "]}";
      first = false;
    }

    // Example 2: the sixteen cases, with the rotational stiffness as printed (1000, 1000, 100) and
    // with the reading (1000, 1000, 1000) that matches the seed's plot ranges (README.md).
    summary << "\n  }";
    struct Variant {
      const char* key;
      const char* file;
      Eigen::Vector3d rotational_stiffness;
    };
    for (const Variant& v : {Variant{"example2", "example2", Eigen::Vector3d(1000, 1000, 100)},
                             Variant{"example2_rot1000", "example2-rot1000", Eigen::Vector3d(1000, 1000, 1000)}}) {
      std::ofstream e2(out_dir / (std::string(v.file) + ".csv"));
      e2 << std::setprecision(12) << "case,lambda,mu,a,stretch_1,stretch_2,stretch_3,wryness_1,wryness_2,wryness_3\n";
      summary << ",\n  \"" << v.key << "\": {\n    \"rotational_stiffness\": [" << v.rotational_stiffness(0) << ", "
              << v.rotational_stiffness(1) << ", " << v.rotational_stiffness(2) << "]";
      for (const std::string& name : seed_measure_function_names()) {
        if (name == "default") continue;
        const MeasureFunctions f = seed_measure_functions(name);
        const seed::Example2Result r = seed::run_example2(name, a_levels, v.rotational_stiffness);
        for (size_t i = 0; i < r.a.size(); ++i) {
          e2 << name << ",\"" << f.lambda.formula() << "\",\"" << f.mu.formula() << "\"," << r.a[i];
          for (int c = 0; c < 6; ++c) e2 << ',' << r.measures[i](c);
          e2 << '\n';
        }
        const double a_end = r.a.empty() ? 0.0 : r.a.back();
        std::cerr << v.key << ", case " << name << " (lambda = " << f.lambda.formula() << ", mu = " << f.mu.formula()
                  << "): reached a = " << a_end << "\n";
        summary << ",\n    \"" << name << "\": {\"a_reached\": " << a_end << ", \"measures_a_end\": [";
        for (int c = 0; c < 6; ++c) summary << (c ? ", " : "") << (r.measures.empty() ? 0.0 : r.measures.back()(c));
        summary << "]}";
      }
      // Small loads: spread of the measures over the sixteen cases, relative to their magnitude.
      std::ofstream sl(out_dir / (std::string(v.file) + "-small-load.csv"));
      sl << std::setprecision(12) << "a,relative_spread\n";
      summary << ",\n    \"small_load_spread\": {";
      bool first_spread = true;
      for (double a : {9e-6, 9e-5, 9e-4, 9e-3, 9e-2}) {
        const double spread = seed::example2_spread(a, v.rotational_stiffness);
        sl << a << ',' << spread << '\n';
        std::cerr << v.key << " at a = " << a << ": largest difference between the sixteen cases, relative to |E|, "
                  << spread << "\n";
        summary << (first_spread ? "" : ", ") << "\"" << a << "\": " << spread;
        first_spread = false;
      }
      summary << "}\n  }";
    }
    summary << "\n}\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "tfmb-beam-flexible-joint-seed: " << e.what() << "\n";
    return 4;
  }
}
