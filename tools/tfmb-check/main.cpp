// clang-format off
// tfmb-check: validate tfmb files against their specs (formats/*.md) and summarise them.
//
// Sample runs:
//   tfmb-check flowmesh.h5 flow.h5      # exit 0 and a summary, or exit 3, one line per problem
//   tfmb-check --list                   # the file kinds this build knows
//   tfmb-check --spec flow              # the Markdown table of a kind's layout
//   tfmb-check --example flow -o ex.h5  # a small valid file of a kind, for an external writer
//   tfmb-check --sidecar flow.h5        # (re)write flow.xdmf of an external writer's file
//   tfmb-check --series -o flow-iterations.xdmf flow.h5  # iterates (iter-*/flow.h5) as times
#include <iostream>
// clang-format on (the sample lines above are run as they stand)

#include "check.hpp"
#include "tfmb/common/cli.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Validate tfmb HDF5 files against their specs and print a summary of each.",
               "tfmb-check"};
  tfmb::check::Options options;
  tfmb::cli::CommonOptions common;
  tfmb::cli::add_common_options(app, common);
  app.add_option("files", options.files, "Files to check (any tfmb kind; identified by /@format)");
  app.add_option("--spec", options.spec_kind, "Print the layout table of a file kind and exit");
  app.add_option("--example", options.example_kind, "Write a small valid file of a kind (-o)");
  app.add_option("-o,--output", options.output, "Output file for --example and --series");
  app.add_flag("--sidecar", options.sidecar,
               "After checking, (re)write each file's XDMF sidecar(s) for ParaView and meshio");
  app.add_flag("--series", options.series,
               "After checking, write a temporal XDMF collection over the files, in the order "
               "given (time 1, 2, ...), to -o");
  app.add_flag("--list", options.list_kinds, "List the file kinds and their versions");
  bool no_summary = false;
  app.add_flag("--no-summary", no_summary, "Only report problems");
  return tfmb::cli::run_main(app, argc, argv, [&] {
    options.summary = !no_summary && !common.quiet;
    return tfmb::check::run(options, std::cout, std::cerr);
  });
}
