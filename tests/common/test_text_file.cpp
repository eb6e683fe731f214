// write_text_atomically (libcommon text_file): whole or not at all.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tfmb/common/errors.hpp"
#include "tfmb/common/text_file.hpp"

namespace fs = std::filesystem;

namespace {

std::string read_all(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(TextFile, WritesWholeAndReplaces) {
  const fs::path dir = fs::temp_directory_path() / ("tfmb_text_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / "a.json";
  tfmb::write_text_atomically(file, "{\"a\": 1}\n");
  EXPECT_EQ(read_all(file), "{\"a\": 1}\n");
  tfmb::write_text_atomically(file, "x");
  EXPECT_EQ(read_all(file), "x");
  EXPECT_FALSE(fs::exists(dir / "a.json.tmp"));
  fs::remove_all(dir);
}

// A write that cannot happen (here: no such directory) throws InternalError naming the file and
// the reason, and leaves nothing behind.
TEST(TextFile, FailedWriteThrowsAndLeavesNothing) {
  const fs::path file =
      fs::temp_directory_path() / ("tfmb_no_such_dir_" + std::to_string(::getpid())) / "s.json";
  try {
    tfmb::write_text_atomically(file, "text");
    FAIL() << "no exception";
  } catch (const tfmb::InternalError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("s.json"), std::string::npos) << what;
    EXPECT_NE(what.find("No such file or directory"), std::string::npos) << what;
  }
  EXPECT_FALSE(fs::exists(file));
  EXPECT_FALSE(fs::exists(file.parent_path()));
}
