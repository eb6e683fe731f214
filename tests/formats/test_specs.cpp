// Each formats/<kind>.md must carry the layout table generated from the schema in code
// (formats/update-specs regenerates it), so spec and code cannot drift apart.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "tfmb/formats/schema.hpp"

namespace tfmb::formats {
namespace {

TEST(FormatsSpecs, EveryKindHasASpecWhoseTableMatchesTheCode) {
  for (const Schema& schema : all_schemas()) {
    const std::string path = std::string(TFMB_SOURCE_DIR) + "/formats/" + schema.kind + ".md";
    std::ifstream in(path);
    ASSERT_TRUE(in) << path << " is missing";
    std::stringstream text;
    text << in.rdbuf();
    const std::string spec = text.str();
    const std::string begin = "<!-- table:begin -->\n", end = "<!-- table:end -->";
    const auto i = spec.find(begin), j = spec.find(end);
    ASSERT_TRUE(i != std::string::npos && j != std::string::npos) << path;
    EXPECT_EQ(spec.substr(i + begin.size(), j - i - begin.size()), markdown_table(schema))
        << path << " is stale: run formats/update-specs";
    EXPECT_NE(spec.find("version " + schema.version()), std::string::npos)
        << path << " does not state version " << schema.version();
  }
}

}  // namespace
}  // namespace tfmb::formats
