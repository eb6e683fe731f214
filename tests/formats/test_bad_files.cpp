// Every reader must refuse a bad file with exit code 3 and one line naming the file and the path
// inside it: not HDF5, truncated, missing dataset, wrong dtype, wrong shape, NaN, Inf, index
// out of range, unknown major version, wrong kind. Run for every kind, in process and through
// the tfmb-check executable.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

#include "check.hpp"
#include "test_support.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/formats/files.hpp"
#include "tfmb/formats/schema.hpp"

namespace tfmb::formats {
namespace {

enum class Corruption {
  not_hdf5, truncated, missing_dataset, wrong_dtype, wrong_shape, nan_value, inf_value,
  index_out_of_range, negative_index, unknown_major_version, huge_major_version, wrong_kind
};

const char* name_of(Corruption c) {
  switch (c) {
    case Corruption::not_hdf5: return "not_hdf5";
    case Corruption::truncated: return "truncated";
    case Corruption::missing_dataset: return "missing_dataset";
    case Corruption::wrong_dtype: return "wrong_dtype";
    case Corruption::wrong_shape: return "wrong_shape";
    case Corruption::nan_value: return "nan_value";
    case Corruption::inf_value: return "inf_value";
    case Corruption::index_out_of_range: return "index_out_of_range";
    case Corruption::negative_index: return "negative_index";
    case Corruption::unknown_major_version: return "unknown_major_version";
    case Corruption::huge_major_version: return "huge_major_version";
    case Corruption::wrong_kind: return "wrong_kind";
  }
  return "?";
}

std::string concrete(std::string path) {
  for (std::size_t pos; (pos = path.find('*')) != std::string::npos;) path.replace(pos, 1, "sample");
  return path;
}

// Writes a corrupted file; returns the path inside the file the message must name ("" if the
// corruption does not apply to this kind).
std::string make_bad_file(const Schema& schema, Corruption corruption,
                          const std::filesystem::path& file) {
  Document document = example_document(schema);
  auto first_rule = [&](auto predicate) -> const DatasetRule* {
    for (const auto& rule : schema.datasets) {
      if (rule.required && predicate(rule)) return &rule;
    }
    return nullptr;
  };
  std::string expected_path = "/";
  switch (corruption) {
    case Corruption::not_hdf5: {
      std::ofstream(file) << "x,y\n0,1\n";
      return file.filename().string();
    }
    case Corruption::truncated: {
      write_document(document, file);
      std::filesystem::resize_file(file, std::filesystem::file_size(file) / 2);
      return file.filename().string();
    }
    case Corruption::missing_dataset: {
      const auto* rule = first_rule([](const DatasetRule&) { return true; });
      if (!rule) return "";
      expected_path = concrete(rule->path);
      document.datasets.erase(expected_path);
      document.attributes.erase(expected_path);
      break;
    }
    case Corruption::wrong_dtype: {
      const auto* rule = first_rule([](const DatasetRule& r) { return r.dtype == h5::DType::float64; });
      if (!rule) return "";
      expected_path = concrete(rule->path);
      auto& value = document.datasets[expected_path];
      value.dtype = h5::DType::int64;
      for (double v : value.floats) value.integers.push_back(static_cast<std::int64_t>(v));
      value.floats.clear();
      break;
    }
    case Corruption::wrong_shape: {
      const auto* rule = first_rule([](const DatasetRule& r) {
        return r.dtype == h5::DType::float64 && (r.shape.empty() || r.shape.back() != "?");
      });
      if (!rule) return "";
      expected_path = concrete(rule->path);
      auto& value = document.datasets[expected_path];
      value.shape.push_back(2);  // one more dimension than the spec allows
      const auto copy = value.floats;
      value.floats.insert(value.floats.end(), copy.begin(), copy.end());
      break;
    }
    case Corruption::nan_value:
    case Corruption::inf_value: {
      const auto* rule = first_rule([](const DatasetRule& r) { return r.dtype == h5::DType::float64; });
      if (!rule) return "";
      expected_path = concrete(rule->path);
      auto& value = document.datasets[expected_path];
      value.floats.back() = corruption == Corruption::nan_value
                                ? std::numeric_limits<double>::quiet_NaN()
                                : std::numeric_limits<double>::infinity();
      break;
    }
    case Corruption::index_out_of_range:
    case Corruption::negative_index: {
      const auto* rule = first_rule([](const DatasetRule& r) { return !r.index_bound.empty(); });
      if (!rule) return "";
      expected_path = concrete(rule->path);
      document.datasets[expected_path].integers.back() =
          corruption == Corruption::index_out_of_range ? 1000000 : rule->index_lower - 5;
      break;
    }
    case Corruption::unknown_major_version:
      document.attributes["/"]["format_version"].text = std::to_string(schema.major + 1) + ".0";
      break;
    case Corruption::huge_major_version:  // more digits than any integer type holds
      document.attributes["/"]["format_version"].text = "99999999999999999999999.0";
      break;
    case Corruption::wrong_kind:
      document.attributes["/"]["format"].text = schema.kind == "flow" ? "tfmb/loads" : "tfmb/flow";
      break;
  }
  write_document(document, file);
  return expected_path;
}

using Param = std::tuple<std::string, Corruption>;
class BadFile : public ::testing::TestWithParam<Param> {};

TEST_P(BadFile, IsRefusedWithOneLocatedLine) {
  const auto& [kind, corruption] = GetParam();
  const Schema* schema = find_schema(kind);
  ASSERT_NE(schema, nullptr);
  const auto dir = test::scratch_dir();
  const auto file = dir / "bad.h5";
  const std::string expected_path = make_bad_file(*schema, corruption, file);
  if (expected_path.empty()) GTEST_SKIP() << "corruption does not apply to " << kind;

  // The reader every stage uses.
  try {
    open_checked(file, kind);
    ADD_FAILURE() << "open_checked accepted a " << name_of(corruption) << " file";
  } catch (const BadInput& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    EXPECT_NE(message.find(expected_path), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }

  // tfmb-check, in process: exit 3 and at least one line naming file and path.
  check::Options options;
  options.files = {file};
  std::ostringstream out, err;
  EXPECT_EQ(check::run(options, out, err), 3);
  EXPECT_NE(err.str().find(file.string() + ": "), std::string::npos) << err.str();
  EXPECT_NE(err.str().find(expected_path), std::string::npos) << err.str();
}

std::string param_name(const ::testing::TestParamInfo<Param>& info) {
  std::string name = std::get<0>(info.param) + "_" + name_of(std::get<1>(info.param));
  for (char& c : name) {
    if (c == '-') c = '_';
  }
  return name;
}

std::vector<std::string> kinds() {
  std::vector<std::string> names;
  for (const auto& s : all_schemas()) names.push_back(s.kind);
  return names;
}

INSTANTIATE_TEST_SUITE_P(
    Formats, BadFile,
    ::testing::Combine(::testing::ValuesIn(kinds()),
                       ::testing::Values(Corruption::not_hdf5, Corruption::truncated,
                                         Corruption::missing_dataset, Corruption::wrong_dtype,
                                         Corruption::wrong_shape, Corruption::nan_value,
                                         Corruption::inf_value, Corruption::index_out_of_range,
                                         Corruption::negative_index,
                                         Corruption::unknown_major_version,
                                         Corruption::huge_major_version,
                                         Corruption::wrong_kind)),
    param_name);

// The executable itself: exit 3 on a bad file, 0 on a good one, 2 on a usage error.
// A boundary names its flap and its side together (tfmb-loads and tfmb-heat find a flap's walls
// by both; tfmb-heat took a flap wall without a side as unwetted): one without the other is
// refused by every reader and by tfmb-check, naming the boundary; neither (a wall of no flap) is
// fine. The model's domain boundaries likewise.
TEST(FlapAndSide, AreRequiredTogether) {
  const auto dir = test::scratch_dir();
  for (const std::string kind : {"flowmesh", "solidmesh", "flow", "thermal", "model"}) {
    const Schema* schema = find_schema(kind);
    ASSERT_NE(schema, nullptr);
    const std::string object =
        kind == "model" ? "/domain/boundaries/sample" : "/mesh/boundaries/sample";
    for (const std::string dropped : {"side", "flap"}) {
      Document document = example_document(*schema);
      ASSERT_TRUE(document.attributes[object].count(dropped)) << kind << " " << dropped;
      document.attributes[object].erase(dropped);
      const auto file = dir / (kind + "-no-" + dropped + ".h5");
      write_document(document, file);
      try {
        open_checked(file, kind);
        ADD_FAILURE() << kind << ": a boundary without '" << dropped << "' was accepted";
      } catch (const BadInput& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(file.string() + ": " + object + ": missing attribute '" + dropped +
                               "', required with attribute '"),
                  std::string::npos)
            << message;
      }
    }
    Document neither = example_document(*schema);
    neither.attributes[object].erase("side");
    neither.attributes[object].erase("flap");
    const auto file = dir / (kind + "-neither.h5");
    write_document(neither, file);
    EXPECT_NO_THROW(open_checked(file, kind)) << kind;
  }
}

TEST(FormatsCheckExecutable, ExitCodes) {
  const auto dir = test::scratch_dir();
  const std::string check = std::string(TFMB_BIN_DIR) + "/tfmb-check";
  const auto good = dir / "good.h5";
  const auto bad = dir / "bad.h5";
  write_document(example_document(*find_schema("flow")), good);
  make_bad_file(*find_schema("flow"), Corruption::nan_value, bad);
  auto run = [](const std::string& command) {
    const int status = std::system((command + " >/dev/null 2>&1").c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  };
  EXPECT_EQ(run(check + " " + good.string()), 0);
  EXPECT_EQ(run(check + " " + bad.string()), 3);
  EXPECT_EQ(run(check + " " + good.string() + " " + bad.string()), 3);
  EXPECT_EQ(run(check + " --no-such-option"), 2);
  EXPECT_EQ(run(check + " --spec no-such-kind"), 2);
  EXPECT_EQ(run(check + " --help"), 0);
}

}  // namespace
}  // namespace tfmb::formats
