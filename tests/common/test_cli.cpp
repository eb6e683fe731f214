// CLI conventions: exceptions map to the documented exit codes.
#include <gtest/gtest.h>

#include <array>

#include "tfmb/common/cli.hpp"
#include "tfmb/common/errors.hpp"

namespace tfmb::cli {
namespace {

int run_with(const std::vector<std::string>& arguments, const std::function<int()>& body) {
  CLI::App app{"test", "tfmb-test"};
  CommonOptions common;
  add_common_options(app, common, true);
  std::vector<std::string> storage = arguments;
  std::vector<char*> argv;
  for (auto& a : storage) argv.push_back(a.data());
  return run_main(app, static_cast<int>(argv.size()), argv.data(), body);
}

TEST(CommonCli, ExitCodes) {
  EXPECT_EQ(run_with({"tfmb-test"}, [] { return 0; }), 0);
  EXPECT_EQ(run_with({"tfmb-test", "--bogus"}, [] { return 0; }), 2);
  EXPECT_EQ(run_with({"tfmb-test"}, []() -> int { throw UsageError("x"); }), 2);
  EXPECT_EQ(run_with({"tfmb-test"}, []() -> int { throw BadInput("x"); }), 3);
  EXPECT_EQ(run_with({"tfmb-test"}, []() -> int { throw NotConverged("x"); }), 1);
  EXPECT_EQ(run_with({"tfmb-test"}, []() -> int { throw std::runtime_error("x"); }), 4);
  EXPECT_EQ(run_with({"tfmb-test", "--version"}, [] { return 5; }), 0);
}

TEST(CommonCli, SplitOverride) {
  EXPECT_EQ(split_override("flow.npr=5.4"), std::make_pair(std::string("flow.npr"), std::string("5.4")));
  EXPECT_THROW(split_override("flow.npr"), UsageError);
  EXPECT_EQ(command_line(2, std::array<char*, 2>{const_cast<char*>("a"), const_cast<char*>("b c")}.data()), "a 'b c'");
}

}  // namespace
}  // namespace tfmb::cli
