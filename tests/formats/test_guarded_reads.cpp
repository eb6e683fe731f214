// Damaged files that crash or hang HDF5 1.10 itself, found by the readers' fuzz target
// (tests/fuzz, issue 23): h5::Reader's guarded child must turn each into one DamagedFile line
// (exit code 3 in the tools) and the test process must survive. Both fail without the guard
// (fork made to fail, so the reader reads unguarded): the first file's root `format` attribute is
// then read from the damaged heap as '' and the file refused as the wrong kind, the damage
// unnamed (the child, reading in its own order, crashed HDF5 on /provenance/input_files); the
// second is refused at a checksum mismatch on /mesh, before the parent reaches the loop.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

#include "test_support.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/formats/files.hpp"
#include "tfmb/formats/flowmesh.hpp"
#include "tfmb/formats/schema.hpp"
#include "tfmb/formats/walldisp.hpp"

namespace tfmb::formats {
namespace {

// The message of the DamagedFile that `read` throws, or "" (and a test failure) if it throws
// nothing or something else.
template <class Read>
std::string damaged_file_message(Read read) {
  try {
    read();
  } catch (const h5::DamagedFile& error) {
    return error.what();
  } catch (const std::exception& error) {
    ADD_FAILURE() << "not a DamagedFile: " << error.what();
    return "";
  }
  ADD_FAILURE() << "the damaged file was accepted";
  return "";
}

// A global heap collection (HDF5 File Format Specification 3.0, III.E): "GCOL", version, 3
// reserved bytes, the collection size (8 bytes), then its objects, each an index (2), a reference
// count (2), 4 reserved bytes and the object's size (8) before its data. The format has no
// checksum over it; HDF5 1.10.8 copies a variable-length string out of it by the stored size.
TEST(GuardedReads, GlobalHeapObjectSizeThatCrashesHdf5IsRefused) {
  const auto dir = test::scratch_dir();
  const auto file = dir / "walldisp.h5";
  write_document(example_document(*find_schema("walldisp")), file);
  std::string bytes = test::read_bytes(file);
  const std::size_t heap = bytes.find("GCOL");
  ASSERT_NE(heap, std::string::npos);
  const std::size_t first_object = heap + 16;
  std::uint16_t index = 0;
  std::memcpy(&index, bytes.data() + first_object, sizeof index);
  ASSERT_EQ(index, 1) << "the first heap object is not where the layout puts it";
  // The size the fuzz run's guarded-child reports showed H5HG_read copying (memcpy of ~1.1e14
  // bytes): far past the collection's 4 KiB.
  const std::uint64_t huge_size = 0x00006764c7100000;
  std::memcpy(bytes.data() + first_object + 8, &huge_size, sizeof huge_size);
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;

  const std::string message = damaged_file_message([&] { read_walldisp(file); });
  EXPECT_NE(message.find(file.string() + ": /"), std::string::npos) << message;
  EXPECT_NE(message.find("crashed the HDF5 library"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

// tfmb-check --example flowmesh as the fuzzer left it (run of 2026-11-27, its slow-unit input
// without the first byte, which chose read_flowmesh): HDF5 loops reading
// /provenance/input_sha256 until the guard's limit kills the child. The loop is finite: about
// 9 s on an idle 2-core machine, more under load, so against the default 10 s the test passed or
// failed with the machine's speed (when the loop ended first, /mesh's checksum refused the
// file). With a 1 s limit the guard always stops it.
TEST(GuardedReads, HeapLoopIsRefusedAfterTheGuardsLimit) {
  const std::filesystem::path file =
      std::filesystem::path(TFMB_SOURCE_DIR) / "tests/data/fuzz-readers/flowmesh-heap-loop.h5";
  struct DefaultLimitAfter {
    ~DefaultLimitAfter() { h5::set_guard_time_limit(std::chrono::seconds(10)); }
  } restore;
  h5::set_guard_time_limit(std::chrono::seconds(1));
  const std::string message = damaged_file_message([&] { read_flowmesh(file); });
  EXPECT_NE(message.find(": /provenance/input_sha256: "), std::string::npos) << message;
  EXPECT_NE(message.find("did not finish in 1 s"), std::string::npos) << message;
}

}  // namespace
}  // namespace tfmb::formats
