// A thin RAII layer over the HDF5 C API (DESIGN.md §4).
//
// Why not the official C++ API: its exceptions do not say which file or which path inside it
// failed. Every error thrown here is a tfmb::BadInput (reading) or tfmb::InternalError (writing)
// whose message is one line: "<file>: <path inside it>: <what is wrong>".
//
// Reading checks dtype (float64 / int64 exactly, any byte order), rank and shape, finiteness of
// every float and, on request, index ranges; an HDF5 call that fails on the file (a checksum
// mismatch, a truncated file) is reported as a damaged file, never taken for a missing object.
// Writing is atomic (<file>.tmp, close, rename), byte-reproducible (object modification times are
// not stored) and in the HDF5 1.10 file format, whose metadata is checksummed.
#pragma once

#include <Eigen/Core>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tfmb/common/errors.hpp"

namespace tfmb::h5 {

// HDF5 stores arrays row-major; these are the in-memory counterparts.
using MatrixXdR = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using MatrixXiR = Eigen::Matrix<std::int64_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

enum class DType { float64, int64, string, other };

struct DatasetInfo {
  DType dtype = DType::other;
  std::string dtype_name;           // human-readable, e.g. "float32", "int64", "string"
  std::vector<std::size_t> shape;   // empty for a scalar
};

// A file HDF5 cannot read as it stands (a checksum mismatch, an address past its end, a heap
// that crashes the library): everything read after the first damage would be its consequence,
// so a validation stops there and reports this one line.
class DamagedFile : public BadInput {
 public:
  using BadInput::BadInput;
};

// Shape expectation for one dimension: std::nullopt accepts any extent.
using Extent = std::optional<std::size_t>;

// Read-only access to one HDF5 file.
class Reader {
 public:
  // Throws BadInput if the file does not exist or is not an HDF5 file, DamagedFile if HDF5
  // cannot open it or if reading it once in a child process crashes or hangs the library (see
  // h5.cpp: parts of the file format carry no checksum and the library trusts them).
  explicit Reader(const std::filesystem::path& file);
  ~Reader();
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;
  Reader(Reader&& other) noexcept;
  Reader& operator=(Reader&&) = delete;

  const std::filesystem::path& path() const { return path_; }

  bool exists(const std::string& object_path) const;
  bool is_group(const std::string& object_path) const;
  bool is_dataset(const std::string& object_path) const;
  // Names of the direct children of a group, sorted. Throws if the group is missing.
  std::vector<std::string> children(const std::string& group_path) const;
  DatasetInfo info(const std::string& dataset_path) const;

  // Any rank; the shape is returned through `shape` if given. Every value must be finite.
  std::vector<double> read_f64(const std::string& dataset_path,
                               std::vector<std::size_t>* shape = nullptr) const;
  std::vector<std::int64_t> read_i64(const std::string& dataset_path,
                                     std::vector<std::size_t>* shape = nullptr) const;

  // Rank-1 float64 dataset, optionally of a given length.
  std::vector<double> read_vector(const std::string& dataset_path, Extent length = {}) const;
  // Rank-2 float64 dataset, optionally with given extents.
  MatrixXdR read_matrix(const std::string& dataset_path, Extent rows = {}, Extent cols = {}) const;
  // Rank-1 / rank-2 int64 datasets whose values must lie in [lower, upper).
  std::vector<std::int64_t> read_index_vector(const std::string& dataset_path, Extent length,
                                              std::int64_t lower, std::int64_t upper) const;
  MatrixXiR read_index_matrix(const std::string& dataset_path, Extent rows, Extent cols,
                              std::int64_t lower, std::int64_t upper) const;
  std::vector<std::string> read_strings(const std::string& dataset_path) const;

  bool has_attr(const std::string& object_path, const std::string& name) const;
  std::vector<std::string> attr_names(const std::string& object_path) const;
  std::string attr_string(const std::string& object_path, const std::string& name) const;
  double attr_f64(const std::string& object_path, const std::string& name) const;  // finite
  std::int64_t attr_i64(const std::string& object_path, const std::string& name) const;
  std::vector<double> attr_f64_vector(const std::string& object_path,
                                      const std::string& name) const;
  // The DType of an attribute (float64, int64, string or other).
  DType attr_dtype(const std::string& object_path, const std::string& name) const;
  // Number of elements of an attribute (1 for a scalar).
  std::size_t attr_size(const std::string& object_path, const std::string& name) const;

  // Throws BadInput("<file>: <object_path>: <what>").
  [[noreturn]] void fail(const std::string& object_path, const std::string& what) const;
  // Throws DamagedFile after an HDF5 call on the file failed, with HDF5's innermost reason (a
  // checksum mismatch, an address past the end of the file). Call it right after the failing
  // call: any other HDF5 call clears the reason.
  [[noreturn]] void fail_hdf5(const std::string& object_path, const std::string& what) const;

 private:
  // H5O_TYPE_GROUP, H5O_TYPE_DATASET, ... of an existing object; a damaged header throws.
  std::int64_t object_type(const std::string& object_path) const;

  std::filesystem::path path_;
  std::int64_t file_id_ = -1;
};

// The bytes of a file a Writer builds in memory (h5.cpp).
struct FileImage;

// Writes one HDF5 file atomically: HDF5 builds it in memory, commit() closes it there, writes
// its bytes to "<file>.tmp" and renames that over <file>. A Writer destroyed without commit()
// removes the temporary file, so a crash or an exception never leaves a partial file that make
// would take as up to date. HDF5 never writes to the disk itself: a write it failed (a full disk)
// left its state broken, and its clean-up at exit then crashed; the Writer's own writes fail
// with an InternalError (exit 4) naming the file and the system's reason.
class Writer {
 public:
  // Creates <file>.tmp at once, so that an unwritable directory fails before any data is written.
  explicit Writer(const std::filesystem::path& file);
  ~Writer();
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  const std::filesystem::path& path() const { return path_; }

  // Creates a group and any missing parents; a no-op if it exists.
  void create_group(const std::string& group_path);

  // Datasets: parents are created as needed; `units` is stored as attribute "units" (SI, "1"
  // for dimensionless and indices), `description` as attribute "description" if not empty.
  void write(const std::string& dataset_path, const std::vector<double>& values,
             const std::string& units, const std::string& description = "");
  void write(const std::string& dataset_path, const MatrixXdR& values, const std::string& units,
             const std::string& description = "");
  void write(const std::string& dataset_path, const std::vector<std::int64_t>& values,
             const std::string& units = "1", const std::string& description = "");
  void write(const std::string& dataset_path, const MatrixXiR& values,
             const std::string& units = "1", const std::string& description = "");
  void write_strings(const std::string& dataset_path, const std::vector<std::string>& values,
                     const std::string& description = "");
  // Any rank: `values` holds the row-major data of an array of the given shape.
  void write_array(const std::string& dataset_path, const std::vector<double>& values,
                   const std::vector<std::size_t>& shape, const std::string& units,
                   const std::string& description = "");
  void write_array(const std::string& dataset_path, const std::vector<std::int64_t>& values,
                   const std::vector<std::size_t>& shape, const std::string& units,
                   const std::string& description = "");
  // Any Eigen dense float expression (column-major, fixed-size, ...).
  template <typename Derived>
  void write_eigen(const std::string& dataset_path, const Eigen::DenseBase<Derived>& values,
                   const std::string& units, const std::string& description = "") {
    write(dataset_path, MatrixXdR(values.template cast<double>()), units, description);
  }

  void set_attr(const std::string& object_path, const std::string& name, const std::string& value);
  void set_attr(const std::string& object_path, const std::string& name, const char* value) {
    set_attr(object_path, name, std::string(value));
  }
  void set_attr(const std::string& object_path, const std::string& name, double value);
  void set_attr(const std::string& object_path, const std::string& name, std::int64_t value);
  void set_attr(const std::string& object_path, const std::string& name, int value) {
    set_attr(object_path, name, static_cast<std::int64_t>(value));
  }
  void set_attr(const std::string& object_path, const std::string& name,
                const std::vector<double>& value);

  // Closes the file, writes it to <file>.tmp and renames that into place. Throws InternalError
  // on failure (the temporary file is removed).
  void commit();

 private:
  void write_raw(const std::string& dataset_path, bool is_float, const void* data,
                 const std::vector<std::size_t>& shape, const std::string& units,
                 const std::string& description);
  void ensure_parents(const std::string& object_path);
  [[noreturn]] void fail(const std::string& object_path, const std::string& what) const;

  std::filesystem::path path_;
  std::filesystem::path tmp_path_;
  std::unique_ptr<FileImage> image_;
  int tmp_fd_ = -1;
  std::int64_t file_id_ = -1;
  bool committed_ = false;
};

// True if the file starts with the HDF5 signature.
bool is_hdf5_file(const std::filesystem::path& file);

// A Reader first reads the whole file in a child process and refuses it as damaged if that child
// crashes or runs longer than this limit plus a second per 10 MB of file (a loop in damaged
// metadata). Default 10 s; tests that feed such a loop set a short one, since how long a finite
// loop runs depends on the machine's speed.
void set_guard_time_limit(std::chrono::seconds base);

}  // namespace tfmb::h5
