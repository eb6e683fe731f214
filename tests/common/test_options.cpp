// OptionTable: one declaration gives the CLI11 option, its --help default and unit, its range
// check and its line in the provenance settings.
#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <optional>
#include <string>
#include <vector>

#include "tfmb/common/cli.hpp"
#include "tfmb/common/options.hpp"

namespace tfmb::cli {
namespace {

// A tool's options with the defaults a tool struct would carry.
struct SampleOptions {
  std::filesystem::path input;
  std::filesystem::path output;
  double pressure = 101325.0;
  double tolerance = 1e-8;
  int max_iterations = 500;
  std::string model = "euler";
  bool exact = false;
  bool first_order_start = true;
  std::optional<double> wall_temperature;
  std::optional<double> throat_area;
  std::vector<std::string> point_loads;
};

struct SampleTool {
  CLI::App app{"sample", "tfmb-sample"};
  SampleOptions options;
  OptionTable table{app};

  SampleTool() {
    table.add("input", options.input, "", "input file")->required();
    table.add_output(options.output, "output file");
    table.add("--pressure", options.pressure, "Pa", "ambient pressure");
    table.add("--tolerance", options.tolerance, "1", "residual drop", range(0.0, 1.0));
    table.add("--max-iterations", options.max_iterations, "1", "iteration limit", range(1, 1e9));
    table.add("--model", options.model, "", "euler or laminar",
              CLI::IsMember({"euler", "laminar"}));
    table.add_flag("--exact", options.exact, "exact Jacobian");
    table.add_flag("--first-order-start,!--no-first-order-start", options.first_order_start,
                   "converge at first order first");
    table.add("--wall-temperature", options.wall_temperature, "K",
              "isothermal walls (default: adiabatic)");
    table.add("--throat-area", options.throat_area, "m^2", "throat area");
    table.add("--point-load", options.point_loads, "", "point loads");
  }

  int run(std::vector<std::string> arguments) {
    arguments.insert(arguments.begin(), "tfmb-sample");
    std::vector<char*> argv;
    for (auto& a : arguments)
      argv.push_back(a.data());
    return run_main(app, static_cast<int>(argv.size()), argv.data(), [] { return 0; });
  }
};

TEST(OptionTable, HelpShowsTheStructDefaultsAndUnits) {
  SampleTool tool;
  const std::string help = tool.app.help();
  EXPECT_NE(help.find("--pressure FLOAT=101325"), std::string::npos) << help;
  EXPECT_NE(help.find("[Pa] ambient pressure"), std::string::npos) << help;
  EXPECT_NE(help.find("--tolerance FLOAT:[0 - 1]=1e-08"), std::string::npos) << help;
  EXPECT_NE(help.find("--max-iterations INT:[1 - 1e+09]=500"), std::string::npos) << help;
  EXPECT_NE(help.find("[1] iteration limit"), std::string::npos) << help;
  EXPECT_NE(help.find("=euler"), std::string::npos) << help;
  EXPECT_NE(help.find("converge at first order first (default: on)"), std::string::npos) << help;
  EXPECT_EQ(help.find("exact Jacobian (default"), std::string::npos) << help;
  // an unset optional shows no default: its help says what its absence means
  EXPECT_NE(help.find("--wall-temperature FLOAT "), std::string::npos) << help;
}

TEST(OptionTable, ValuesOutsideTheRangeAreAUsageError) {
  EXPECT_EQ(SampleTool().run({"in.h5", "-o", "out.h5", "--max-iterations", "0"}), 2);
  EXPECT_EQ(SampleTool().run({"in.h5", "-o", "out.h5", "--tolerance", "2"}), 2);
  EXPECT_EQ(SampleTool().run({"in.h5", "-o", "out.h5", "--tolerance", "nan"}), 2);
  EXPECT_EQ(SampleTool().run({"in.h5", "-o", "out.h5", "--model", "sa"}), 2);
  EXPECT_EQ(
      SampleTool().run({"in.h5", "-o", "out.h5", "--max-iterations", "1", "--tolerance", "1"}), 0);
}

TEST(OptionTable, SettingsListEveryOptionWithItsParsedValue) {
  SampleTool tool;
  ASSERT_EQ(
      tool.run({"in.h5", "-o", "out.h5", "--pressure", "2e5", "--no-first-order-start",
                "--throat-area", "0.25", "--point-load", "a:end:0,1", "--point-load", "b \"q\""}),
      0);
  EXPECT_EQ(tool.table.settings_toml(),
            "input = \"in.h5\"\n"
            "output = \"out.h5\"\n"
            "pressure = 2e+05  # Pa\n"
            "tolerance = 1e-08  # 1\n"
            "max_iterations = 500  # 1\n"
            "model = \"euler\"\n"
            "exact = false\n"
            "first_order_start = false\n"
            "# wall_temperature: not set\n"
            "throat_area = 0.25  # m^2\n"
            "point_load = [\"a:end:0,1\", \"b \\\"q\\\"\"]\n");
  // valid TOML whose values read back as parsed
  const toml::table settings = toml::parse(tool.table.settings_toml());
  EXPECT_EQ(settings["pressure"].value<double>(), 2e5);
  EXPECT_EQ(settings["tolerance"].value<double>(), 1e-8);
  EXPECT_EQ(settings["max_iterations"].value<std::int64_t>(), 500);
  EXPECT_EQ(settings["first_order_start"].value<bool>(), false);
  EXPECT_EQ(settings["point_load"][1].value<std::string>(), "b \"q\"");
  EXPECT_FALSE(settings.contains("wall_temperature"));
}

TEST(OptionTable, SubcommandSettingsNameTheSubcommand) {
  CLI::App app{"sample", "tfmb-sample"};
  auto* forces = app.add_subcommand("forces", "forces");
  int samples = 8;
  OptionTable table(*forces);
  table.add("--samples", samples, "1", "pieces per segment");
  std::vector<std::string> arguments = {"tfmb-sample", "forces", "--samples", "4"};
  std::vector<char*> argv;
  for (auto& a : arguments)
    argv.push_back(a.data());
  app.parse(static_cast<int>(argv.size()), argv.data());
  EXPECT_EQ(table.settings_toml(), "command = \"forces\"\nsamples = 4  # 1\n");
}

TEST(OptionTable, NumbersAreShortestRoundTripText) {
  EXPECT_EQ(detail::shortest_text(0.1), "0.1");
  EXPECT_EQ(detail::shortest_text(287.05), "287.05");
  EXPECT_EQ(toml_float(10000.0), "10000.0");
  EXPECT_EQ(toml_float(5e-2), "0.05");
  EXPECT_EQ(toml_float(-1.0 / 0.0), "-inf");
  EXPECT_EQ(toml_string("a\\b\tc"), "\"a\\\\b\\u0009c\"");
}

}  // namespace
}  // namespace tfmb::cli
