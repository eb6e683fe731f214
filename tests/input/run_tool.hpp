// Runs a tfmb executable from build/bin and captures its exit code and stderr.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace tfmb::test {

struct ToolResult {
  int exit_code = -1;
  std::string stderr_text;
};

inline ToolResult run_tool(const std::string& arguments, const std::filesystem::path& scratch) {
  const auto err = scratch / "stderr.txt";
  const std::string command = std::string(TFMB_BIN_DIR) + "/" + arguments + " 2> " + err.string() + " > /dev/null";
  const int status = std::system(command.c_str());
  ToolResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err);
  std::stringstream text;
  text << in.rdbuf();
  result.stderr_text = text.str();
  return result;
}

// A fresh scratch directory under the build tree.
inline std::filesystem::path scratch_dir(const std::string& name) {
  const auto dir = std::filesystem::path(TFMB_BINARY_DIR) / "test-scratch" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline void write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file);
  out << text;
}

}  // namespace tfmb::test
