// Command-line conventions shared by every tool (DESIGN.md §5): --version, -o/--output, -v/-q,
// --threads, --set key=value, and the mapping of exceptions to the documented exit codes. Tools
// declare their own options once, through cli::OptionTable (options.hpp).
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "tfmb/common/log.hpp"

namespace tfmb::cli {

struct CommonOptions {
  int verbose_count = 0;  // -v, repeatable
  bool quiet = false;     // -q
  int threads = 0;        // --threads; 0 = OpenMP default (OMP_NUM_THREADS or all cores)
  Verbosity verbosity() const;
};

// The project version, e.g. "0.1.0".
std::string version();

// Adds --version, -v/--verbose, -q/--quiet, --threads.
void add_common_options(CLI::App& app, CommonOptions& options, bool with_threads = false);
// Adds a required -o/--output file option.
CLI::Option* add_output_option(CLI::App& app, std::filesystem::path& output,
                               const std::string& what);
// Adds repeatable --set key=value overrides of case.toml settings.
CLI::Option* add_set_option(CLI::App& app, std::vector<std::string>& overrides);
// Splits "key=value"; throws UsageError if there is no '='.
std::pair<std::string, std::string> split_override(const std::string& assignment);

// The command line as one shell-quoted string (stored in /provenance).
std::string command_line(int argc, char** argv);

// Parses argv and runs `body`, turning exceptions into exit codes and one "<tool>: error: ..."
// line on stderr: CLI11 parse errors and UsageError -> 2, BadInput -> 3, NotConverged -> 1,
// everything else -> 4. --help and --version exit 0.
int run_main(CLI::App& app, int argc, char** argv, const std::function<int()>& body);

}  // namespace tfmb::cli
