// tfmb-check: identify a tfmb file, validate it against its spec, summarise it for a person.
#pragma once

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace tfmb::check {

struct Options {
  std::vector<std::filesystem::path> files;
  std::string spec_kind;          // --spec: print the Markdown table of a kind
  std::string example_kind;       // --example: write a small valid file of a kind
  std::filesystem::path output;   // with --example and --series
  bool sidecar = false;           // --sidecar: (re)write each valid file's XDMF sidecar
  bool series = false;            // --series: a temporal XDMF collection over the files (-o)
  bool list_kinds = false;        // --list
  bool summary = true;            // --no-summary turns the human summary off
};

// Validates each file; writes summaries to `out` and one line per problem to `err`.
// Returns 0 if every file is valid, 3 otherwise.
int check_files(const Options& options, std::ostream& out, std::ostream& err);

// Runs the selected action (check, --spec, --example, --list, --sidecar, --series); returns the
// exit code.
int run(const Options& options, std::ostream& out, std::ostream& err);

}  // namespace tfmb::check
