// A libFuzzer target over the file readers (issue 23): the bytes after the first are an HDF5 file,
// the first byte chooses which reader takes it: a kind's typed reader (read_model, read_flow, ...)
// by its place in all_schemas() (the order `tfmb-check --list` prints), or, past the last kind,
// what tfmb-check does with any file (schema_of, validate collecting every problem,
// read_document). A bad input must end in tfmb::BadInput (exit code 3 in the tools); any other
// exception escaping, a crash, a hang, a leak or an out-of-bounds access is a finding.
//
// The readers open files by path (h5::Reader pre-reads each file in a forked child before
// trusting it, and that guard is part of what is tested), so each input is written to a file of
// this process first. Built with -DTFMB_FUZZ=ON and clang (libFuzzer); without it, the same code
// is linked with replay_main.cpp, which runs it over given files (the seeds' ctest entry).
//
// The guard's child is a copy of the fuzzer: a crash there is the guard doing its job (the parent
// turns it into DamagedFile), not a finding, so the child must not write libFuzzer's crash
// artifact. After fork, the child drops libFuzzer's handlers of the signals the guard expects and
// the sanitizer's death callback (libFuzzer's, which writes the artifact); the sanitizer's report
// of a SEGV goes to $TFMB_FUZZ_CHILD_REPORTS.<pid> when that is set (else nowhere: the guard
// already sends the child's stderr to /dev/null), so the run can show whether a crash was in
// HDF5 (expected) or in tfmb's own pre-reading code (a finding).
//
// LeakSanitizer cannot see an HDF5 handle that a reader forgets to close (the library's ID tables
// keep it reachable), so after every input the harness counts the objects HDF5 still has open:
// more than none is a finding (abort). Leaks that HDF5 1.10 itself makes on some damaged files
// (a metadata cache entry dropped on a failed decode) are suppressed by lsan.supp.
#include <pthread.h>
#include <unistd.h>

#include <hdf5.h>

#include <csignal>
#include <cstdlib>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <string>

#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/formats/files.hpp"
#include "tfmb/formats/flow.hpp"
#include "tfmb/formats/flowmesh.hpp"
#include "tfmb/formats/loads.hpp"
#include "tfmb/formats/material_db.hpp"
#include "tfmb/formats/materials.hpp"
#include "tfmb/formats/model.hpp"
#include "tfmb/formats/schema.hpp"
#include "tfmb/formats/solidmesh.hpp"
#include "tfmb/formats/strain.hpp"
#include "tfmb/formats/structure.hpp"
#include "tfmb/formats/thermal.hpp"
#include "tfmb/formats/walldisp.hpp"

#ifdef TFMB_FUZZ_LIBFUZZER
#include <sanitizer/common_interface_defs.h>
#endif

namespace {

namespace fs = std::filesystem;
namespace formats = tfmb::formats;

using TypedReader = std::function<void(const fs::path&)>;

// Every kind's typed reader, by the schema's kind name. A kind of all_schemas() missing here is
// read by the generic path only (and the check below says so once).
const std::map<std::string, TypedReader>& typed_readers() {
  static const std::map<std::string, TypedReader> readers = {
      {"model", [](const fs::path& f) { formats::read_model(f); }},
      {"flowmesh", [](const fs::path& f) { formats::read_flowmesh(f); }},
      {"solidmesh", [](const fs::path& f) { formats::read_solidmesh(f); }},
      {"flow", [](const fs::path& f) { formats::read_flow(f); }},
      {"thermal", [](const fs::path& f) { formats::read_thermal(f); }},
      {"material-db", [](const fs::path& f) { formats::read_material_db(f); }},
      {"materials", [](const fs::path& f) { formats::read_materials(f); }},
      {"loads", [](const fs::path& f) { formats::read_loads(f); }},
      {"walldisp", [](const fs::path& f) { formats::read_walldisp(f); }},
      {"structure", [](const fs::path& f) { formats::read_structure(f); }},
      {"strain", [](const fs::path& f) { formats::read_strain(f); }},
  };
  return readers;
}

// What tfmb-check does with a file of any kind.
void check_any_kind(const fs::path& file) {
  const tfmb::h5::Reader reader(file);
  const formats::Schema& schema = formats::schema_of(reader);
  formats::validate(reader, schema, false);
  formats::read_document(reader);
}

// One file per process (libFuzzer's -jobs run several), removed at exit.
struct InputFile {
  fs::path path =
      fs::temp_directory_path() / ("tfmb-fuzz-readers-" + std::to_string(getpid()) + ".h5");
  ~InputFile() {
    std::error_code ec;
    fs::remove(path, ec);
  }
};

#ifdef TFMB_FUZZ_LIBFUZZER
void quiet_guarded_child() {
  for (const int signal : {SIGABRT, SIGBUS, SIGILL, SIGFPE})
    std::signal(signal, SIG_DFL);
  __sanitizer_set_death_callback(nullptr);
  if (const char* reports = std::getenv("TFMB_FUZZ_CHILD_REPORTS"))
    __sanitizer_set_report_path(reports);
}
#endif

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
#ifdef TFMB_FUZZ_LIBFUZZER
  pthread_atfork(nullptr, nullptr, quiet_guarded_child);
#endif
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1)
    return 0;
  static InputFile input;
  const auto& schemas = formats::all_schemas();
  const std::size_t choice = data[0] % (schemas.size() + 1);
  {
    std::FILE* out = std::fopen(input.path.c_str(), "wb");
    if (out == nullptr)
      return 0;  // no temporary file: nothing to test (the run's log shows no progress)
    const std::size_t written = std::fwrite(data + 1, 1, size - 1, out);
    const bool closed = std::fclose(out) == 0;
    if (written != size - 1 || !closed)
      return 0;
  }
  try {
    if (choice == schemas.size()) {
      check_any_kind(input.path);
    } else {
      const auto reader = typed_readers().find(schemas[choice].kind);
      if (reader == typed_readers().end())
        check_any_kind(input.path);
      else
        reader->second(input.path);
    }
  } catch (const tfmb::BadInput&) {
    // The expected end of a bad input (h5::DamagedFile included).
  }
  const ssize_t still_open = H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL);
  if (still_open != 0) {
    std::fprintf(stderr, "fuzz_readers: %zd HDF5 objects still open after the reader returned\n",
                 still_open);
    std::abort();
  }
  return 0;
}
