// The HDF5 layer: typed round trips, located errors, atomic writes.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <limits>

#include <hdf5.h>

#include "tfmb/common/errors.hpp"
#include "tfmb/common/geometry.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/common/hash.hpp"

namespace tfmb::h5 {
namespace {

std::filesystem::path scratch(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / "tfmb-tests" / "common";
  std::filesystem::create_directories(dir);
  auto path = dir / name;
  std::filesystem::remove(path);
  return path;
}

TEST(CommonH5, TypedRoundTrip) {
  const auto path = scratch("typed.h5");
  MatrixXdR points(3, 2);
  points << 0, 1, 2, 3, 4, 5.5;
  MatrixXiR cells(1, 3);
  cells << 0, 1, 2;
  {
    Writer file(path);
    file.write("/mesh/points", points, "m", "coordinates");
    file.write("/mesh/cells", cells);
    file.write("/values", std::vector<double>{1.5, -2.0}, "Pa");
    file.write_strings("/names", {"inner", "outer"});
    file.set_attr("/", "format", "tfmb/test");
    file.set_attr("/mesh", "depth", 1.25);
    file.set_attr("/mesh", "count", std::int64_t{7});
    file.set_attr("/mesh", "vector", std::vector<double>{1, 2, 3});
    file.commit();
  }
  Reader file(path);
  EXPECT_EQ(file.read_matrix("/mesh/points", 3, 2), points);
  EXPECT_EQ(file.read_index_matrix("/mesh/cells", {}, 3, 0, 3), cells);
  EXPECT_EQ(file.read_vector("/values", 2), (std::vector<double>{1.5, -2.0}));
  EXPECT_EQ(file.read_strings("/names"), (std::vector<std::string>{"inner", "outer"}));
  EXPECT_EQ(file.attr_string("/", "format"), "tfmb/test");
  EXPECT_EQ(file.attr_string("/values", "units"), "Pa");
  EXPECT_EQ(file.attr_string("/mesh/points", "description"), "coordinates");
  EXPECT_DOUBLE_EQ(file.attr_f64("/mesh", "depth"), 1.25);
  EXPECT_EQ(file.attr_i64("/mesh", "count"), 7);
  EXPECT_EQ(file.attr_f64_vector("/mesh", "vector"), (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(file.children("/mesh"), (std::vector<std::string>{"cells", "points"}));
  EXPECT_TRUE(file.is_group("/mesh"));
  EXPECT_TRUE(file.is_dataset("/mesh/points"));
  EXPECT_FALSE(file.exists("/no/such/thing"));
}

void expect_located(const std::function<void()>& action, const std::string& file,
                    const std::string& object, const std::string& what) {
  try {
    action();
    ADD_FAILURE() << "no error";
  } catch (const BadInput& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(file + ": " + object + ": "), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
  }
}

TEST(CommonH5, ErrorsNameFileAndPath) {
  const auto path = scratch("errors.h5");
  {
    Writer file(path);
    file.write("/a", std::vector<double>{1.0, std::numeric_limits<double>::quiet_NaN()}, "m");
    file.write("/idx", std::vector<std::int64_t>{0, 5}, "1");
    file.write("/m", MatrixXdR(MatrixXdR::Zero(2, 3)), "m");
    file.commit();
  }
  Reader file(path);
  const std::string name = path.string();
  expect_located([&] { file.read_vector("/a"); }, name, "/a", "non-finite");
  expect_located([&] { file.read_vector("/missing"); }, name, "/missing", "missing dataset");
  expect_located([&] { file.read_vector("/idx"); }, name, "/idx", "wrong dtype int64");
  expect_located([&] { file.read_index_vector("/idx", {}, 0, 5); }, name, "/idx", "out of range");
  expect_located([&] { file.read_matrix("/m", {}, 2); }, name, "/m", "wrong shape (2,3)");
  expect_located([&] { file.attr_string("/m", "units2"); }, name, "/m", "missing attribute");
}

// A dataset whose declared shape is larger than what the file stores (here an extendible
// dataset grown to 2^40 rows without writing them, as a flipped byte in a shape would declare):
// refused with a located message instead of a 16 TB allocation.
TEST(CommonH5, DeclaredShapeBeyondTheStoredDataIsRefused) {
  const auto path = scratch("huge.h5");
  {
    const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    const hsize_t dims[2] = {4, 2}, max_dims[2] = {H5S_UNLIMITED, 2}, chunk[2] = {4, 2};
    const hid_t space = H5Screate_simple(2, dims, max_dims);
    const hid_t plist = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(plist, 2, chunk);
    const hid_t dataset = H5Dcreate2(file, "/big", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, plist, H5P_DEFAULT);
    const double values[8] = {1, 2, 3, 4, 5, 6, 7, 8};
    H5Dwrite(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values);
    const hsize_t huge[2] = {hsize_t{1} << 40, 2};
    H5Dset_extent(dataset, huge);
    H5Dclose(dataset);
    H5Pclose(plist);
    H5Sclose(space);
    H5Fclose(file);
  }
  Reader file(path);
  expect_located([&] { file.read_matrix("/big"); }, path.string(), "/big", "declares");
}

TEST(CommonH5, NotHdf5AndMissingFile) {
  const auto text = scratch("text.h5");
  { std::ofstream(text) << "hello"; }
  EXPECT_THROW(Reader{text}, BadInput);
  EXPECT_THROW(Reader{scratch("none.h5")}, BadInput);
}

TEST(CommonH5, UncommittedWriteLeavesNoFile) {
  const auto path = scratch("atomic.h5");
  {
    Writer file(path);
    file.write("/a", std::vector<double>{1.0}, "m");
    // destroyed without commit(), as after an exception
  }
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(path.string() + ".tmp"));
}

TEST(CommonHash, KnownDigest) {
  // FIPS 180-2 test vector.
  EXPECT_EQ(sha256_text("abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(CommonGeometry, PolylineHelpers) {
  using geometry::Point;
  const geometry::Polyline line{Point(0, 0), Point(3, 4), Point(3, 10)};
  const auto s = geometry::cumulative_length(line);
  EXPECT_DOUBLE_EQ(s.back(), 11.0);
  EXPECT_TRUE(geometry::point_at_length(line, 8.0).isApprox(Point(3, 7)));
  EXPECT_DOUBLE_EQ(geometry::interpolate({0, 1, 2}, {0, 10, 30}, 1.5), 20.0);
  const auto crossing = geometry::segment_intersection(Point(0, 0), Point(2, 2), Point(0, 2), Point(2, 0));
  ASSERT_TRUE(crossing.has_value());
  EXPECT_TRUE(crossing->isApprox(Point(1, 1)));
  EXPECT_FALSE(geometry::segment_intersection(Point(0, 0), Point(1, 0), Point(0, 1), Point(1, 1)));
  EXPECT_DOUBLE_EQ(geometry::signed_area({Point(0, 0), Point(1, 0), Point(1, 1), Point(0, 1)}), 1.0);
}

}  // namespace
}  // namespace tfmb::h5
