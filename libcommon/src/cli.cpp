#include "tfmb/common/cli.hpp"

#include <iostream>
#include <new>

#include "tfmb/common/errors.hpp"

#ifndef TFMB_VERSION
#define TFMB_VERSION "unknown"
#endif

namespace tfmb::cli {

Verbosity CommonOptions::verbosity() const {
  if (quiet) return Verbosity::quiet;
  if (verbose_count >= 2) return Verbosity::debug;
  if (verbose_count == 1) return Verbosity::verbose;
  return Verbosity::normal;
}

std::string version() { return TFMB_VERSION; }

void add_common_options(CLI::App& app, CommonOptions& options, bool with_threads) {
  app.set_version_flag("--version", std::string(app.get_name()) + " " + version());
  app.add_flag("-v,--verbose", options.verbose_count, "More progress output (repeat for debug)");
  app.add_flag("-q,--quiet", options.quiet, "Only warnings, errors and the final summary line");
  if (with_threads) {
    app.add_option("--threads", options.threads,
                   "Number of OpenMP threads (0: OMP_NUM_THREADS or all cores); results are "
                   "deterministic for a given thread count")
        ->check(CLI::NonNegativeNumber);
  }
}

CLI::Option* add_output_option(CLI::App& app, std::filesystem::path& output,
                               const std::string& what) {
  return app.add_option("-o,--output", output, "Output file: " + what)->required();
}

CLI::Option* add_set_option(CLI::App& app, std::vector<std::string>& overrides) {
  return app.add_option("--set", overrides,
                        "Override a case.toml setting, e.g. --set flow.nozzle_pressure_ratio=5.423 (repeatable)")
      ->take_all()
      ->allow_extra_args(false);
}

std::pair<std::string, std::string> split_override(const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw UsageError("--set expects key=value, got '" + assignment + "'");
  }
  return {assignment.substr(0, eq), assignment.substr(eq + 1)};
}

std::string command_line(int argc, char** argv) {
  std::string result;
  for (int i = 0; i < argc; ++i) {
    std::string arg = argv[i];
    const bool needs_quotes = arg.empty() || arg.find_first_of(" \t'\"$\\;&|<>*?()") != std::string::npos;
    if (needs_quotes) {
      std::string quoted = "'";
      for (char c : arg) quoted += (c == '\'') ? std::string("'\\''") : std::string(1, c);
      arg = quoted + "'";
    }
    result += (i ? " " : "") + arg;
  }
  return result;
}

int run_main(CLI::App& app, int argc, char** argv, const std::function<int()>& body) {
  const std::string tool = app.get_name();
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << tool << ": error: " << e.what() << " (see --help)\n";
    return static_cast<int>(ExitCode::usage);
  }
  try {
    return body();
  } catch (const Error& e) {
    std::cerr << tool << ": error: " << e.what() << '\n';
    return static_cast<int>(e.code());
  } catch (const std::bad_alloc&) {
    std::cerr << tool << ": error: out of memory\n";
    return static_cast<int>(ExitCode::internal);
  } catch (const std::exception& e) {
    std::cerr << tool << ": internal error: " << e.what() << '\n';
    return static_cast<int>(ExitCode::internal);
  }
}

}  // namespace tfmb::cli
