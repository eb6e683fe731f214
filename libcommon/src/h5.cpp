#include "tfmb/common/h5.hpp"

#include <fcntl.h>
#include <hdf5.h>
#include <poll.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <new>
#include <numeric>
#include <set>
#include <sstream>

#include "tfmb/common/errors.hpp"

static_assert(sizeof(hid_t) == sizeof(std::int64_t), "hid_t is expected to be 64-bit");

namespace tfmb::h5 {
namespace {

// HDF5 prints its own error stack to stderr by default; we report one located line instead.
void silence_hdf5_errors() {
  static const bool silenced = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)silenced;
}

// The innermost entry of HDF5's error stack after a failed call ("incorrect metadata checksum
// after all read attempts", "truncated file: eof = ..."), to say why a damaged file was refused.
// Must be called before any other HDF5 call, which would clear the stack.
std::string hdf5_cause() {
  std::string cause;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned n, const H5E_error2_t* error, void* data) -> herr_t {
        if (n == 0 && error->desc)
          *static_cast<std::string*>(data) = error->desc;
        return 0;
      },
      &cause);
  return cause;
}

// Closes an HDF5 identifier of any kind when it goes out of scope.
class Handle {
 public:
  explicit Handle(hid_t id = H5I_INVALID_HID) : id_(id) {}
  ~Handle() { reset(); }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& o) noexcept : id_(o.id_) { o.id_ = H5I_INVALID_HID; }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  void reset() {
    if (id_ >= 0) {
      switch (H5Iget_type(id_)) {
        case H5I_FILE: H5Fclose(id_); break;
        case H5I_GROUP: H5Gclose(id_); break;
        case H5I_DATASET: H5Dclose(id_); break;
        case H5I_DATASPACE: H5Sclose(id_); break;
        case H5I_DATATYPE: H5Tclose(id_); break;
        case H5I_ATTR: H5Aclose(id_); break;
        case H5I_GENPROP_LST: H5Pclose(id_); break;
        default: H5Idec_ref(id_); break;
      }
    }
    id_ = H5I_INVALID_HID;
  }

 private:
  hid_t id_;
};

std::string dtype_name_of(hid_t type) {
  const H5T_class_t cls = H5Tget_class(type);
  const std::size_t size = H5Tget_size(type);
  switch (cls) {
    case H5T_FLOAT: return "float" + std::to_string(8 * size);
    case H5T_INTEGER:
      return std::string(H5Tget_sign(type) == H5T_SGN_NONE ? "uint" : "int") +
             std::to_string(8 * size);
    case H5T_STRING: return "string";
    case H5T_COMPOUND: return "compound";
    case H5T_ARRAY: return "array";
    case H5T_ENUM: return "enum";
    default: return "other";
  }
}

DType dtype_of(hid_t type) {
  const H5T_class_t cls = H5Tget_class(type);
  const std::size_t size = H5Tget_size(type);
  if (cls == H5T_FLOAT && size == 8) return DType::float64;
  if (cls == H5T_INTEGER && size == 8 && H5Tget_sign(type) == H5T_SGN_2) return DType::int64;
  if (cls == H5T_STRING) return DType::string;
  return DType::other;
}

std::string shape_text(const std::vector<std::size_t>& shape) {
  std::ostringstream out;
  out << "(";
  for (std::size_t i = 0; i < shape.size(); ++i) out << (i ? "," : "") << shape[i];
  if (shape.size() == 1) out << ",";
  out << ")";
  return out.str();
}

std::size_t element_count(const std::vector<std::size_t>& shape) {
  return std::accumulate(shape.begin(), shape.end(), std::size_t{1}, std::multiplies<>());
}

hid_t string_type() {
  hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  return type;
}

// Names of a group's links, unsorted, from one walk of its link index in the order it is stored:
// asking for them by position (H5Lget_name_by_idx) or in name order makes HDF5 build a table of
// a large group's links, and HDF5 1.10 frees that table's unfilled entries when a damaged heap
// stops the build (a crash in H5G__link_release_table). False if the walk failed (the HDF5 error
// stack says why).
bool link_names(hid_t group, std::vector<std::string>& names) {
  hsize_t index = 0;
  return H5Literate(
             group, H5_INDEX_NAME, H5_ITER_NATIVE, &index,
             [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
               static_cast<std::vector<std::string>*>(data)->emplace_back(name);
               return 0;
             },
             &names) >= 0;
}

// The same for an object's attributes (more than 8 are kept in a heap, as links are).
bool attribute_names(hid_t object, std::vector<std::string>& names) {
  hsize_t index = 0;
  return H5Aiterate2(
             object, H5_INDEX_NAME, H5_ITER_NATIVE, &index,
             [](hid_t, const char* name, const H5A_info_t*, void* data) -> herr_t {
               static_cast<std::vector<std::string>*>(data)->emplace_back(name);
               return 0;
             },
             &names) >= 0;
}

// ---------------------------------------------------------------------------------------------
// Reading a file once in a child process before trusting it
//
// The 1.10 file format checksums the metadata, but not the global heap that holds variable-length
// strings (every string attribute and dataset of a tfmb file), nor the heap references stored in
// a string dataset's values, nor anything in files of the older format (external writers, h5py
// defaults). HDF5 1.10 follows a damaged heap object's size or address without checking it: it
// crashes (SIGSEGV in H5HG_read) or loops forever (a zeroed object size in H5HG's cache
// deserialize). No API reads those structures without trusting them, so a child process reads
// every attribute and every dataset the library would have to decode for us first; if it dies or
// hangs, the file is refused with one line naming the object it was reading.

// Shared with the child: what it is reading, for the parent's message if it dies there.
struct GuardProgress {
  char object[512];
  char what[256];
};

void note(GuardProgress* progress, const std::string& object, const std::string& what) {
  std::snprintf(progress->object, sizeof progress->object, "%s", object.c_str());
  std::snprintf(progress->what, sizeof progress->what, "%s", what.c_str());
}

// Above this a value is not read in the child (the parent refuses or reads it itself).
constexpr std::size_t guard_read_limit = std::size_t{1} << 29;

// Reads `count` elements of an attribute (dataset == false) or dataset of file type `type`, in
// the type's native form (variable-length strings as C strings), and frees what HDF5 allocated.
void read_values(hid_t object, bool dataset, hid_t type, hid_t space, hsize_t count) {
  if (count == 0)
    return;
  const bool vlen_string = H5Tget_class(type) == H5T_STRING && H5Tis_variable_str(type) > 0;
  Handle memory_type(vlen_string ? string_type() : H5Tget_native_type(type, H5T_DIR_DEFAULT));
  if (!memory_type.valid())
    return;
  const std::size_t size = H5Tget_size(memory_type.get());
  if (size == 0 || count > guard_read_limit / size)
    return;
  std::vector<unsigned char> buffer(static_cast<std::size_t>(count) * size);
  const herr_t read =
      dataset ? H5Dread(object, memory_type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data())
              : H5Aread(object, memory_type.get(), buffer.data());
  if (read >= 0 && (vlen_string || H5Tdetect_class(memory_type.get(), H5T_VLEN) > 0)) {
    H5Dvlen_reclaim(memory_type.get(), space, H5P_DEFAULT, buffer.data());
  }
}

// Reads the object at `path` (its header, attributes and, for a dataset, values the library
// decodes: strings, chunked or compact storage) and recurses into groups, each object once.
// Failures are skipped: the parent reports them where it meets them, with the reason.
void read_object(hid_t file, const std::string& path, std::set<haddr_t>& seen,
                 GuardProgress* progress) {
  note(progress, path, "reading the object header");
  H5O_info_t info;
  if (H5Oget_info_by_name(file, path.c_str(), &info, H5P_DEFAULT) < 0)
    return;
  if (!seen.insert(info.addr).second)
    return;  // a hard link to an object already read
  Handle object(H5Oopen(file, path.c_str(), H5P_DEFAULT));
  if (!object.valid())
    return;

  note(progress, path, "reading the attributes");
  std::vector<std::string> attributes;
  if (!attribute_names(object.get(), attributes))
    return;
  for (const std::string& name : attributes) {
    note(progress, path, "reading attribute '" + name + "'");
    Handle attr(H5Aopen(object.get(), name.c_str(), H5P_DEFAULT));
    if (!attr.valid())
      continue;
    Handle type(H5Aget_type(attr.get()));
    Handle space(H5Aget_space(attr.get()));
    if (!type.valid() || !space.valid())
      continue;
    const hssize_t count = H5Sget_simple_extent_npoints(space.get());
    if (count > 0) {
      read_values(attr.get(), false, type.get(), space.get(), static_cast<hsize_t>(count));
    }
  }

  if (info.type == H5O_TYPE_DATASET) {
    note(progress, path, "reading the dataset");
    Handle type(H5Dget_type(object.get()));
    Handle space(H5Dget_space(object.get()));
    Handle plist(H5Dget_create_plist(object.get()));
    if (!type.valid() || !space.valid() || !plist.valid())
      return;
    const hssize_t count = H5Sget_simple_extent_npoints(space.get());
    if (count <= 0)
      return;
    // Plain contiguous numbers are copied from the file as they are; what the library decodes
    // (heap references of strings, chunk indexes, compact storage in the header) is read here.
    const bool decoded = H5Tdetect_class(type.get(), H5T_STRING) > 0 ||
                         H5Tdetect_class(type.get(), H5T_VLEN) > 0 ||
                         H5Pget_layout(plist.get()) != H5D_CONTIGUOUS;
    // A shape declaring more than the file stores is refused by the parent before reading.
    const double declared =
        static_cast<double>(count) * static_cast<double>(H5Tget_size(type.get()));
    const bool plausible = H5Pget_nfilters(plist.get()) > 0 ||
                           declared <= static_cast<double>(H5Dget_storage_size(object.get()));
    if (decoded && plausible) {
      read_values(object.get(), true, type.get(), space.get(), static_cast<hsize_t>(count));
    }
  } else if (info.type == H5O_TYPE_GROUP) {
    note(progress, path, "reading the group's links");
    std::vector<std::string> links;
    if (!link_names(object.get(), links))
      return;
    for (const std::string& name : links) {
      const std::string child = (path == "/" ? "/" : path + "/") + name;
      H5L_info_t link;
      if (H5Lget_info(file, child.c_str(), &link, H5P_DEFAULT) < 0 || link.type != H5L_TYPE_HARD) {
        continue;  // soft and external links are not followed by the readers either
      }
      read_object(file, child, seen, progress);
    }
  }
}

std::chrono::seconds guard_base_limit{10};  // set_guard_time_limit()

// Reads the whole file in a child process; throws DamagedFile if the child crashes or hangs.
// Returns without a verdict where no child can be made (the reads then run unguarded).
void read_in_guarded_child(const std::filesystem::path& file) {
  void* shared = mmap(nullptr, sizeof(GuardProgress), PROT_READ | PROT_WRITE,
                      MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  if (shared == MAP_FAILED)
    return;
  auto* progress = new (shared) GuardProgress{};
  note(progress, "/", "opening the file");
  // The child holds the write end of a pipe until it ends: the parent sees the end at once.
  int pipe_ends[2];
  if (pipe2(pipe_ends, O_CLOEXEC) != 0) {
    munmap(shared, sizeof(GuardProgress));
    return;
  }
  const pid_t pid = fork();
  if (pid < 0) {
    close(pipe_ends[0]);
    close(pipe_ends[1]);
    munmap(shared, sizeof(GuardProgress));
    return;
  }
  if (pid == 0) {
    close(pipe_ends[0]);
    // A crash report (a sanitizer's) is not for the user: the parent words it.
    const int null = open("/dev/null", O_WRONLY);
    if (null >= 0)
      dup2(null, STDERR_FILENO);
    try {
      const hid_t id = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
      if (id >= 0) {
        std::set<haddr_t> seen;
        read_object(id, "/", seen, progress);
      }
    } catch (...) {
      // Out of memory and the like: not a crash of the library; the parent reads and reports.
    }
    // _exit: no atexit handlers, so the parent's open HDF5 files are not flushed from here.
    _exit(0);
  }
  close(pipe_ends[1]);
  // The child reads metadata and strings: milliseconds for tfmb's files. The limit only stops a
  // loop; it grows with the file for chunked data read from a slow disk.
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(file, ec);
  const auto limit = guard_base_limit + std::chrono::seconds(ec ? 0 : bytes / 10'000'000);
  const auto deadline = std::chrono::steady_clock::now() + limit;
  bool hung = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      hung = true;
      break;
    }
    pollfd end{pipe_ends[0], POLLIN, 0};
    const int ready = poll(&end, 1, static_cast<int>(left.count()));
    if (ready < 0 && errno == EINTR)
      continue;
    if (ready < 0)
      break;  // cannot watch: wait for the child below
    if (ready > 0) {
      char byte;
      if (read(pipe_ends[0], &byte, 1) <= 0)
        break;  // end of file: the child has ended
    }
  }
  close(pipe_ends[0]);
  if (hung)
    kill(pid, SIGKILL);
  int status = 0;
  pid_t done;
  do {
    done = waitpid(pid, &status, 0);
  } while (done < 0 && errno == EINTR);
  const std::string object = progress->object;
  const std::string what = progress->what;
  munmap(shared, sizeof(GuardProgress));
  if (done != pid)
    return;  // e.g. SIGCHLD ignored: the child's end is not ours to know
  const std::string where = file.string() + ": " + object + ": ";
  if (hung) {
    throw DamagedFile(where + what + " did not finish in " + std::to_string(limit.count()) +
                      " s (a loop in damaged HDF5 metadata): damaged file");
  }
  if (WIFSIGNALED(status)) {
    throw DamagedFile(where + what + " crashed the HDF5 library (" + strsignal(WTERMSIG(status)) +
                      "): damaged file");
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw DamagedFile(where + what + " crashed the HDF5 library (exit status " +
                      std::to_string(WEXITSTATUS(status)) + "): damaged file");
  }
}

}  // namespace

bool is_hdf5_file(const std::filesystem::path& file) {
  silence_hdf5_errors();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return false;
  return H5Fis_hdf5(file.c_str()) > 0;
}

void set_guard_time_limit(std::chrono::seconds base) {
  guard_base_limit = base;
}

// ---------------------------------------------------------------------------------------------
// Reader

Reader::Reader(const std::filesystem::path& file) : path_(file) {
  silence_hdf5_errors();
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) {
    throw BadInput(file.string() + ": no such file");
  }
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw BadInput(file.string() + ": not a regular file");
  }
  if (H5Fis_hdf5(file.c_str()) <= 0) {
    throw BadInput(file.string() + ": not an HDF5 file (no HDF5 signature)");
  }
  read_in_guarded_child(file);
  file_id_ = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file_id_ < 0) {
    const std::string cause = hdf5_cause();
    throw DamagedFile(file.string() + ": cannot open as HDF5 (" +
                      (cause.empty() ? std::string("truncated or corrupted file?") : cause) +
                      "): damaged file");
  }
}

Reader::~Reader() {
  if (file_id_ >= 0) H5Fclose(file_id_);
}

Reader::Reader(Reader&& other) noexcept : path_(std::move(other.path_)), file_id_(other.file_id_) {
  other.file_id_ = -1;
}

void Reader::fail(const std::string& object_path, const std::string& what) const {
  throw BadInput(path_.string() + ": " + object_path + ": " + what);
}

void Reader::fail_hdf5(const std::string& object_path, const std::string& what) const {
  const std::string cause = hdf5_cause();
  throw DamagedFile(path_.string() + ": " + object_path + ": " + what +
                    (cause.empty() ? std::string() : " (" + cause + ")") + ": damaged file");
}

std::int64_t Reader::object_type(const std::string& object_path) const {
  H5O_info_t info;
  if (H5Oget_info_by_name(file_id_, object_path.c_str(), &info, H5P_DEFAULT) < 0) {
    fail_hdf5(object_path, "cannot read the object header");
  }
  return info.type;
}

bool Reader::exists(const std::string& object_path) const {
  if (object_path == "/") return true;
  // H5Lexists fails on a missing intermediate group, so walk the path one link at a time. A
  // failure (rather than "no") is a damaged file, reported as such: taken for absence it became
  // a list of "missing" objects that hid the cause.
  std::string partial;
  std::size_t start = 1;
  while (start <= object_path.size()) {
    std::size_t end = object_path.find('/', start);
    if (end == std::string::npos) end = object_path.size();
    partial = object_path.substr(0, end);
    const htri_t link = H5Lexists(file_id_, partial.c_str(), H5P_DEFAULT);
    if (link < 0)
      fail_hdf5(partial, "cannot read the group's links");
    if (link == 0)
      return false;
    const htri_t object = H5Oexists_by_name(file_id_, partial.c_str(), H5P_DEFAULT);
    if (object < 0)
      fail_hdf5(partial, "cannot resolve the link");
    if (object == 0)
      return false;
    // Below a dataset nothing exists (and H5Lexists would fail on the path).
    if (end < object_path.size() && object_type(partial) != H5O_TYPE_GROUP)
      return false;
    start = end + 1;
  }
  return true;
}

bool Reader::is_group(const std::string& object_path) const {
  return exists(object_path) && object_type(object_path) == H5O_TYPE_GROUP;
}

bool Reader::is_dataset(const std::string& object_path) const {
  return exists(object_path) && object_type(object_path) == H5O_TYPE_DATASET;
}

std::vector<std::string> Reader::children(const std::string& group_path) const {
  if (!is_group(group_path)) fail(group_path, "missing group");
  Handle group(H5Gopen2(file_id_, group_path.c_str(), H5P_DEFAULT));
  if (!group.valid())
    fail_hdf5(group_path, "cannot open group");
  std::vector<std::string> names;
  if (!link_names(group.get(), names))
    fail_hdf5(group_path, "cannot list group");
  std::sort(names.begin(), names.end());
  return names;
}

DatasetInfo Reader::info(const std::string& dataset_path) const {
  if (!exists(dataset_path)) fail(dataset_path, "missing dataset");
  if (!is_dataset(dataset_path)) fail(dataset_path, "is a group, expected a dataset");
  Handle dataset(H5Dopen2(file_id_, dataset_path.c_str(), H5P_DEFAULT));
  if (!dataset.valid())
    fail_hdf5(dataset_path, "cannot open dataset");
  Handle type(H5Dget_type(dataset.get()));
  Handle space(H5Dget_space(dataset.get()));
  if (!type.valid() || !space.valid())
    fail_hdf5(dataset_path, "cannot read type or shape");
  DatasetInfo result;
  result.dtype = dtype_of(type.get());
  result.dtype_name = dtype_name_of(type.get());
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0)
    fail_hdf5(dataset_path, "cannot read shape");
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  result.shape.assign(dims.begin(), dims.end());
  return result;
}

namespace {
// A dataset without filters stores every value it declares; one that declares more than the
// file holds is corrupted (a flipped byte in its shape: 2^40 rows made every reader try to
// allocate 16 TB and die out of memory, exit 4) and is refused before anything is allocated.
// (Compressed datasets may store less: tfmb writes none.) A variable-length string is stored as
// a 16-byte reference into the global heap: `element_bytes` 8 is a safe lower bound for it.
void check_stored_size(const Reader& reader, hid_t dataset, const std::string& path,
                       const std::vector<std::size_t>& shape, std::size_t element_bytes) {
  double declared = static_cast<double>(element_bytes);
  for (std::size_t d : shape)
    declared *= static_cast<double>(d);
  if (declared <= 0.0)
    return;
  Handle plist(H5Dget_create_plist(dataset));
  const hsize_t stored = H5Dget_storage_size(dataset);
  if (plist.valid() && H5Pget_nfilters(plist.get()) == 0 &&
      declared > static_cast<double>(stored)) {
    std::ostringstream what;
    what << "shape " << shape_text(shape) << " declares " << declared
         << " bytes but the file stores " << stored << " (corrupted or truncated file?)";
    reader.fail(path, what.str());
  }
}

template <typename T>
std::vector<T> read_numeric(const Reader& reader, hid_t file_id, const std::string& path,
                            DType expected, hid_t memory_type, std::vector<std::size_t>* shape) {
  const DatasetInfo info = reader.info(path);
  if (info.dtype != expected) {
    reader.fail(path, "wrong dtype " + info.dtype_name + ", expected " +
                          (expected == DType::float64 ? "float64" : "int64"));
  }
  Handle dataset(H5Dopen2(file_id, path.c_str(), H5P_DEFAULT));
  if (!dataset.valid())
    reader.fail_hdf5(path, "cannot open dataset");
  check_stored_size(reader, dataset.get(), path, info.shape, sizeof(T));
  std::vector<T> values(element_count(info.shape));
  if (!values.empty() &&
      H5Dread(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0) {
    reader.fail_hdf5(path, "cannot read data");
  }
  if (shape) *shape = info.shape;
  return values;
}
}  // namespace

std::vector<double> Reader::read_f64(const std::string& dataset_path,
                                     std::vector<std::size_t>* shape) const {
  std::vector<std::size_t> local_shape;
  auto values = read_numeric<double>(*this, file_id_, dataset_path, DType::float64,
                                     H5T_NATIVE_DOUBLE, &local_shape);
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      std::ostringstream what;
      what << "non-finite value " << values[i] << " at flat index " << i;
      if (local_shape.size() == 2 && local_shape[1] > 0) {
        what << " (row " << i / local_shape[1] << ", column " << i % local_shape[1] << ")";
      }
      fail(dataset_path, what.str());
    }
  }
  if (shape) *shape = local_shape;
  return values;
}

std::vector<std::int64_t> Reader::read_i64(const std::string& dataset_path,
                                           std::vector<std::size_t>* shape) const {
  return read_numeric<std::int64_t>(*this, file_id_, dataset_path, DType::int64,
                                    H5T_NATIVE_INT64, shape);
}

namespace {
void check_shape(const Reader& reader, const std::string& path,
                 const std::vector<std::size_t>& shape, std::size_t rank,
                 std::initializer_list<Extent> extents) {
  bool ok = shape.size() == rank;
  std::size_t d = 0;
  for (const Extent& e : extents) {
    if (ok && e && shape[d] != *e) ok = false;
    ++d;
  }
  if (!ok) {
    std::ostringstream expected;
    expected << "(";
    d = 0;
    for (const Extent& e : extents) {
      expected << (d ? "," : "") << (e ? std::to_string(*e) : std::string("*"));
      ++d;
    }
    if (rank == 1) expected << ",";
    expected << ")";
    reader.fail(path, "wrong shape " + shape_text(shape) + ", expected " + expected.str());
  }
}

template <typename T>
void check_range(const Reader& reader, const std::string& path, const std::vector<T>& values,
                 std::int64_t lower, std::int64_t upper) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (values[i] < lower || values[i] >= upper) {
      reader.fail(path, "index " + std::to_string(values[i]) + " at flat index " +
                            std::to_string(i) + " out of range [" + std::to_string(lower) + ", " +
                            std::to_string(upper) + ")");
    }
  }
}
}  // namespace

std::vector<double> Reader::read_vector(const std::string& dataset_path, Extent length) const {
  std::vector<std::size_t> shape;
  auto values = read_f64(dataset_path, &shape);
  check_shape(*this, dataset_path, shape, 1, {length});
  return values;
}

MatrixXdR Reader::read_matrix(const std::string& dataset_path, Extent rows, Extent cols) const {
  std::vector<std::size_t> shape;
  auto values = read_f64(dataset_path, &shape);
  check_shape(*this, dataset_path, shape, 2, {rows, cols});
  return Eigen::Map<MatrixXdR>(values.data(), static_cast<Eigen::Index>(shape[0]),
                               static_cast<Eigen::Index>(shape[1]));
}

std::vector<std::int64_t> Reader::read_index_vector(const std::string& dataset_path,
                                                    Extent length, std::int64_t lower,
                                                    std::int64_t upper) const {
  std::vector<std::size_t> shape;
  auto values = read_i64(dataset_path, &shape);
  check_shape(*this, dataset_path, shape, 1, {length});
  check_range(*this, dataset_path, values, lower, upper);
  return values;
}

MatrixXiR Reader::read_index_matrix(const std::string& dataset_path, Extent rows, Extent cols,
                                    std::int64_t lower, std::int64_t upper) const {
  std::vector<std::size_t> shape;
  auto values = read_i64(dataset_path, &shape);
  check_shape(*this, dataset_path, shape, 2, {rows, cols});
  check_range(*this, dataset_path, values, lower, upper);
  return Eigen::Map<MatrixXiR>(values.data(), static_cast<Eigen::Index>(shape[0]),
                               static_cast<Eigen::Index>(shape[1]));
}

std::vector<std::string> Reader::read_strings(const std::string& dataset_path) const {
  const DatasetInfo info = this->info(dataset_path);
  if (info.dtype != DType::string) {
    fail(dataset_path, "wrong dtype " + info.dtype_name + ", expected string");
  }
  if (info.shape.size() > 1) fail(dataset_path, "wrong shape " + shape_text(info.shape) + ", expected (n,)");
  Handle dataset(H5Dopen2(file_id_, dataset_path.c_str(), H5P_DEFAULT));
  if (!dataset.valid())
    fail_hdf5(dataset_path, "cannot open dataset");
  Handle file_type(H5Dget_type(dataset.get()));
  if (H5Tis_variable_str(file_type.get()) <= 0) fail(dataset_path, "expected variable-length strings");
  check_stored_size(*this, dataset.get(), dataset_path, info.shape, 8);
  Handle memory_type(string_type());
  const std::size_t n = element_count(info.shape);
  std::vector<char*> raw(n, nullptr);
  if (n > 0 && H5Dread(dataset.get(), memory_type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT,
                       raw.data()) < 0) {
    fail_hdf5(dataset_path, "cannot read strings");
  }
  std::vector<std::string> result;
  for (char* s : raw) result.emplace_back(s ? s : "");
  if (n > 0) {
    Handle space(H5Dget_space(dataset.get()));
    H5Dvlen_reclaim(memory_type.get(), space.get(), H5P_DEFAULT, raw.data());
  }
  return result;
}

bool Reader::has_attr(const std::string& object_path, const std::string& name) const {
  if (!exists(object_path)) return false;
  const htri_t found = H5Aexists_by_name(file_id_, object_path.c_str(), name.c_str(), H5P_DEFAULT);
  if (found < 0)
    fail_hdf5(object_path, "cannot read the attributes");
  return found > 0;
}

std::vector<std::string> Reader::attr_names(const std::string& object_path) const {
  if (!exists(object_path)) fail(object_path, "missing object");
  Handle object(H5Oopen(file_id_, object_path.c_str(), H5P_DEFAULT));
  if (!object.valid())
    fail_hdf5(object_path, "cannot open object");
  std::vector<std::string> names;
  if (!attribute_names(object.get(), names))
    fail_hdf5(object_path, "cannot list the attributes");
  std::sort(names.begin(), names.end());
  return names;
}

namespace {
Handle open_attr(const Reader& reader, hid_t file_id, const std::string& object_path,
                 const std::string& name) {
  if (!reader.has_attr(object_path, name)) reader.fail(object_path, "missing attribute '" + name + "'");
  Handle attr(H5Aopen_by_name(file_id, object_path.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT));
  if (!attr.valid())
    reader.fail_hdf5(object_path, "cannot open attribute '" + name + "'");
  return attr;
}

std::size_t attr_count(hid_t attr) {
  Handle space(H5Aget_space(attr));
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank <= 0) return 1;
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  std::size_t n = 1;
  for (hsize_t d : dims) n *= d;
  return n;
}
}  // namespace

DType Reader::attr_dtype(const std::string& object_path, const std::string& name) const {
  Handle attr = open_attr(*this, file_id_, object_path, name);
  Handle type(H5Aget_type(attr.get()));
  return dtype_of(type.get());
}

std::size_t Reader::attr_size(const std::string& object_path, const std::string& name) const {
  Handle attr = open_attr(*this, file_id_, object_path, name);
  return attr_count(attr.get());
}

std::string Reader::attr_string(const std::string& object_path, const std::string& name) const {
  Handle attr = open_attr(*this, file_id_, object_path, name);
  Handle type(H5Aget_type(attr.get()));
  if (H5Tget_class(type.get()) != H5T_STRING) {
    fail(object_path, "attribute '" + name + "' has dtype " + dtype_name_of(type.get()) +
                          ", expected string");
  }
  if (attr_count(attr.get()) != 1) fail(object_path, "attribute '" + name + "' is not a scalar");
  if (H5Tis_variable_str(type.get()) > 0) {
    Handle memory_type(string_type());
    char* raw = nullptr;
    if (H5Aread(attr.get(), memory_type.get(), &raw) < 0) {
      fail_hdf5(object_path, "cannot read attribute '" + name + "'");
    }
    std::string value = raw ? raw : "";
    Handle space(H5Aget_space(attr.get()));
    H5Dvlen_reclaim(memory_type.get(), space.get(), H5P_DEFAULT, &raw);
    return value;
  }
  // Fixed-length strings (written by h5py with np.bytes_ or by other tools) are accepted too.
  const std::size_t size = H5Tget_size(type.get());
  std::string value(size, '\0');
  Handle memory_type(H5Tcopy(H5T_C_S1));
  H5Tset_size(memory_type.get(), size);
  if (H5Aread(attr.get(), memory_type.get(), value.data()) < 0) {
    fail_hdf5(object_path, "cannot read attribute '" + name + "'");
  }
  value.resize(std::min(value.size(), value.find('\0')));
  return value;
}

double Reader::attr_f64(const std::string& object_path, const std::string& name) const {
  Handle attr = open_attr(*this, file_id_, object_path, name);
  Handle type(H5Aget_type(attr.get()));
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_FLOAT && cls != H5T_INTEGER) {
    fail(object_path, "attribute '" + name + "' has dtype " + dtype_name_of(type.get()) +
                          ", expected a number");
  }
  if (attr_count(attr.get()) != 1) fail(object_path, "attribute '" + name + "' is not a scalar");
  double value = 0;
  if (H5Aread(attr.get(), H5T_NATIVE_DOUBLE, &value) < 0) {
    fail_hdf5(object_path, "cannot read attribute '" + name + "'");
  }
  if (!std::isfinite(value)) {
    std::ostringstream what;
    what << "attribute '" << name << "' is not finite (" << value << ")";
    fail(object_path, what.str());
  }
  return value;
}

std::int64_t Reader::attr_i64(const std::string& object_path, const std::string& name) const {
  Handle attr = open_attr(*this, file_id_, object_path, name);
  Handle type(H5Aget_type(attr.get()));
  if (H5Tget_class(type.get()) != H5T_INTEGER) {
    fail(object_path, "attribute '" + name + "' has dtype " + dtype_name_of(type.get()) +
                          ", expected an integer");
  }
  if (attr_count(attr.get()) != 1) fail(object_path, "attribute '" + name + "' is not a scalar");
  std::int64_t value = 0;
  if (H5Aread(attr.get(), H5T_NATIVE_INT64, &value) < 0) {
    fail_hdf5(object_path, "cannot read attribute '" + name + "'");
  }
  return value;
}

std::vector<double> Reader::attr_f64_vector(const std::string& object_path,
                                            const std::string& name) const {
  Handle attr = open_attr(*this, file_id_, object_path, name);
  Handle type(H5Aget_type(attr.get()));
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_FLOAT && cls != H5T_INTEGER) {
    fail(object_path, "attribute '" + name + "' has dtype " + dtype_name_of(type.get()) +
                          ", expected numbers");
  }
  std::vector<double> values(attr_count(attr.get()));
  if (H5Aread(attr.get(), H5T_NATIVE_DOUBLE, values.data()) < 0) {
    fail_hdf5(object_path, "cannot read attribute '" + name + "'");
  }
  for (double v : values) {
    if (!std::isfinite(v)) fail(object_path, "attribute '" + name + "' has a non-finite value");
  }
  return values;
}

// ---------------------------------------------------------------------------------------------
// Writer

namespace {
// Settings of every object the Writer creates (the root group through the file's creation list):
// no modification times, so that two runs give identical bytes; and attributes kept in the
// object header whatever their number. HDF5 moves more than 8 into a heap of their own, which
// the 1.10 format allows, and HDF5 1.10.8 crashes copying an object whose heap holds strings
// (H5Ocopy, h5py's Group.copy: /convergence of a flow file has 20 attributes); in the header,
// they are under its checksum too.
void set_object_creation(hid_t plist) {
  H5Pset_obj_track_times(plist, 0);
  H5Pset_attr_phase_change(plist, 65535, 0);
}
}  // namespace

struct FileImage {
  void* data = nullptr;      // HDF5's buffer, handed over when the file is closed
  std::size_t capacity = 0;  // its size in bytes (the file ends before, see image_size)
};

namespace {

// The core driver keeps the file in one buffer that it grows with image_realloc and releases
// with image_free when the file is closed: these callbacks keep it at that point instead.
void* image_malloc(std::size_t size, H5FD_file_image_op_t, void* udata) {
  void* data = std::malloc(size);
  if (data)
    static_cast<FileImage*>(udata)->capacity = size;
  return data;
}
void* image_memcpy(void* to, const void* from, std::size_t size, H5FD_file_image_op_t, void*) {
  return std::memcpy(to, from, size);
}
void* image_realloc(void* data, std::size_t size, H5FD_file_image_op_t, void* udata) {
  void* grown = std::realloc(data, size);
  if (grown)
    static_cast<FileImage*>(udata)->capacity = size;
  return grown;
}
herr_t image_free(void* data, H5FD_file_image_op_t operation, void* udata) {
  if (operation == H5FD_FILE_IMAGE_OP_FILE_CLOSE) {
    static_cast<FileImage*>(udata)->data = data;
  } else {
    std::free(data);
  }
  return 0;
}
// One FileImage per Writer: property list copies share it.
void* image_udata_copy(void* udata) {
  return udata;
}
herr_t image_udata_free(void*) {
  return 0;
}

// The length of a closed file's image: the end-of-file address of its superblock (version 2 or 3,
// what the 1.10 format bounds give: signature 8 bytes, version, offset and length sizes, flags,
// then base, extension and end-of-file addresses of 8 bytes). 0 if the image is not one.
std::size_t image_size(const FileImage& image) {
  const auto* bytes = static_cast<const unsigned char*>(image.data);
  static const unsigned char signature[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};
  if (!bytes || image.capacity < 48 || std::memcmp(bytes, signature, 8) != 0 ||
      (bytes[8] != 2 && bytes[8] != 3) || bytes[9] != 8) {
    return 0;
  }
  std::uint64_t end = 0;
  for (int i = 7; i >= 0; --i)
    end = (end << 8) | bytes[28 + i];  // little-endian
  return end <= image.capacity ? static_cast<std::size_t>(end) : 0;
}

}  // namespace

Writer::Writer(const std::filesystem::path& file) : path_(file) {
  silence_hdf5_errors();
  tmp_path_ = file;
  tmp_path_ += ".tmp";
  std::error_code ec;
  std::filesystem::remove(tmp_path_, ec);
  if (file.has_parent_path() && !file.parent_path().empty()) {
    std::filesystem::create_directories(file.parent_path(), ec);
  }
  tmp_fd_ = ::open(tmp_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (tmp_fd_ < 0) {
    throw InternalError(tmp_path_.string() + ": cannot create file (" + std::strerror(errno) + ")");
  }
  Handle fcpl(H5Pcreate(H5P_FILE_CREATE));
  set_object_creation(fcpl.get());
  // The HDF5 1.10 file format checksums its metadata (superblock, object headers, B-trees,
  // heaps of link names), so a damaged file fails to open or read with a checksum error that
  // the Reader reports, where the 1.8-compatible default format let the library follow a
  // flipped address or size and crash (issue 23). The upper bound is pinned too, so that a newer
  // HDF5 still writes files that 1.10 readers (Debian's h5py) open.
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS));
  // In memory (the core driver without a backing store, growing by 1 MiB): see the class comment.
  image_ = std::make_unique<FileImage>();
  H5FD_file_image_callbacks_t callbacks = {image_malloc, image_memcpy,     image_realloc,
                                           image_free,   image_udata_copy, image_udata_free,
                                           image_.get()};
  if (H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V110, H5F_LIBVER_V110) < 0 ||
      H5Pset_fapl_core(fapl.get(), std::size_t{1} << 20, false) < 0 ||
      H5Pset_file_image_callbacks(fapl.get(), &callbacks) < 0) {
    ::close(tmp_fd_);
    std::filesystem::remove(tmp_path_, ec);
    throw InternalError(tmp_path_.string() + ": cannot set up the HDF5 1.10 file format in memory");
  }
  file_id_ = H5Fcreate(tmp_path_.c_str(), H5F_ACC_TRUNC, fcpl.get(), fapl.get());
  if (file_id_ < 0) {
    const std::string cause = hdf5_cause();
    ::close(tmp_fd_);
    std::filesystem::remove(tmp_path_, ec);
    throw InternalError(tmp_path_.string() + ": cannot create the HDF5 file in memory (" + cause +
                        ")");
  }
}

Writer::~Writer() {
  // In memory: closing cannot fail on a disk, whatever went wrong before.
  if (file_id_ >= 0) H5Fclose(file_id_);
  if (image_)
    std::free(image_->data);
  if (tmp_fd_ >= 0)
    ::close(tmp_fd_);
  if (!committed_) {
    std::error_code ec;
    std::filesystem::remove(tmp_path_, ec);
  }
}

void Writer::fail(const std::string& object_path, const std::string& what) const {
  throw InternalError(path_.string() + ": " + object_path + ": " + what);
}

void Writer::create_group(const std::string& group_path) {
  if (group_path.empty() || group_path == "/") return;
  ensure_parents(group_path + "/x");
}

void Writer::ensure_parents(const std::string& object_path) {
  std::size_t pos = 1;
  while ((pos = object_path.find('/', pos)) != std::string::npos) {
    const std::string partial = object_path.substr(0, pos);
    if (H5Lexists(file_id_, partial.c_str(), H5P_DEFAULT) <= 0) {
      Handle gcpl(H5Pcreate(H5P_GROUP_CREATE));
      set_object_creation(gcpl.get());
      Handle group(H5Gcreate2(file_id_, partial.c_str(), H5P_DEFAULT, gcpl.get(), H5P_DEFAULT));
      if (!group.valid()) fail(partial, "cannot create group");
    }
    ++pos;
  }
}

void Writer::write_raw(const std::string& dataset_path, bool is_float, const void* data,
                       const std::vector<std::size_t>& shape, const std::string& units,
                       const std::string& description) {
  if (file_id_ < 0) fail(dataset_path, "file already committed");
  ensure_parents(dataset_path);
  std::vector<hsize_t> dims(shape.begin(), shape.end());
  Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr));
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE));
  set_object_creation(dcpl.get());
  const hid_t file_type = is_float ? H5T_IEEE_F64LE : H5T_STD_I64LE;
  const hid_t memory_type = is_float ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT64;
  Handle dataset(H5Dcreate2(file_id_, dataset_path.c_str(), file_type, space.get(), H5P_DEFAULT,
                            dcpl.get(), H5P_DEFAULT));
  if (!dataset.valid()) fail(dataset_path, "cannot create dataset (exists already?)");
  if (element_count(shape) > 0 &&
      H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
    fail(dataset_path, "cannot write dataset (out of memory?)");
  }
  dataset.reset();
  set_attr(dataset_path, "units", units);
  if (!description.empty()) set_attr(dataset_path, "description", description);
}

void Writer::write(const std::string& dataset_path, const std::vector<double>& values,
                   const std::string& units, const std::string& description) {
  write_raw(dataset_path, true, values.data(), {values.size()}, units, description);
}

void Writer::write(const std::string& dataset_path, const MatrixXdR& values,
                   const std::string& units, const std::string& description) {
  write_raw(dataset_path, true, values.data(),
            {static_cast<std::size_t>(values.rows()), static_cast<std::size_t>(values.cols())},
            units, description);
}

void Writer::write(const std::string& dataset_path, const std::vector<std::int64_t>& values,
                   const std::string& units, const std::string& description) {
  write_raw(dataset_path, false, values.data(), {values.size()}, units, description);
}

void Writer::write(const std::string& dataset_path, const MatrixXiR& values,
                   const std::string& units, const std::string& description) {
  write_raw(dataset_path, false, values.data(),
            {static_cast<std::size_t>(values.rows()), static_cast<std::size_t>(values.cols())},
            units, description);
}

void Writer::write_array(const std::string& dataset_path, const std::vector<double>& values,
                         const std::vector<std::size_t>& shape, const std::string& units,
                         const std::string& description) {
  if (element_count(shape) != values.size()) fail(dataset_path, "shape does not match data size");
  write_raw(dataset_path, true, values.data(), shape, units, description);
}

void Writer::write_array(const std::string& dataset_path, const std::vector<std::int64_t>& values,
                         const std::vector<std::size_t>& shape, const std::string& units,
                         const std::string& description) {
  if (element_count(shape) != values.size()) fail(dataset_path, "shape does not match data size");
  write_raw(dataset_path, false, values.data(), shape, units, description);
}

void Writer::write_strings(const std::string& dataset_path, const std::vector<std::string>& values,
                           const std::string& description) {
  if (file_id_ < 0) fail(dataset_path, "file already committed");
  ensure_parents(dataset_path);
  hsize_t n = values.size();
  Handle space(H5Screate_simple(1, &n, nullptr));
  Handle type(string_type());
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE));
  set_object_creation(dcpl.get());
  Handle dataset(H5Dcreate2(file_id_, dataset_path.c_str(), type.get(), space.get(), H5P_DEFAULT,
                            dcpl.get(), H5P_DEFAULT));
  if (!dataset.valid()) fail(dataset_path, "cannot create dataset (exists already?)");
  std::vector<const char*> raw;
  for (const auto& s : values) raw.push_back(s.c_str());
  if (n > 0 && H5Dwrite(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data()) < 0) {
    fail(dataset_path, "cannot write dataset");
  }
  dataset.reset();
  set_attr(dataset_path, "units", std::string("1"));
  if (!description.empty()) set_attr(dataset_path, "description", description);
}

namespace {
void write_attr(hid_t file_id, const std::string& object_path, const std::string& name,
                hid_t file_type, hid_t memory_type, hid_t space, const void* data,
                const std::function<void(const std::string&)>& fail) {
  if (H5Aexists_by_name(file_id, object_path.c_str(), name.c_str(), H5P_DEFAULT) > 0) {
    H5Adelete_by_name(file_id, object_path.c_str(), name.c_str(), H5P_DEFAULT);
  }
  Handle attr(H5Acreate_by_name(file_id, object_path.c_str(), name.c_str(), file_type, space,
                                H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  if (!attr.valid()) fail("cannot create attribute '" + name + "'");
  if (H5Awrite(attr.get(), memory_type, data) < 0) fail("cannot write attribute '" + name + "'");
}
}  // namespace

void Writer::set_attr(const std::string& object_path, const std::string& name,
                      const std::string& value) {
  if (object_path != "/" && H5Lexists(file_id_, object_path.c_str(), H5P_DEFAULT) <= 0) {
    create_group(object_path);
  }
  Handle type(string_type());
  Handle space(H5Screate(H5S_SCALAR));
  const char* raw = value.c_str();
  write_attr(file_id_, object_path, name, type.get(), type.get(), space.get(), &raw,
             [&](const std::string& what) { fail(object_path, what); });
}

void Writer::set_attr(const std::string& object_path, const std::string& name, double value) {
  if (object_path != "/" && H5Lexists(file_id_, object_path.c_str(), H5P_DEFAULT) <= 0) {
    create_group(object_path);
  }
  Handle space(H5Screate(H5S_SCALAR));
  write_attr(file_id_, object_path, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, space.get(), &value,
             [&](const std::string& what) { fail(object_path, what); });
}

void Writer::set_attr(const std::string& object_path, const std::string& name,
                      std::int64_t value) {
  if (object_path != "/" && H5Lexists(file_id_, object_path.c_str(), H5P_DEFAULT) <= 0) {
    create_group(object_path);
  }
  Handle space(H5Screate(H5S_SCALAR));
  write_attr(file_id_, object_path, name, H5T_STD_I64LE, H5T_NATIVE_INT64, space.get(), &value,
             [&](const std::string& what) { fail(object_path, what); });
}

void Writer::set_attr(const std::string& object_path, const std::string& name,
                      const std::vector<double>& value) {
  if (object_path != "/" && H5Lexists(file_id_, object_path.c_str(), H5P_DEFAULT) <= 0) {
    create_group(object_path);
  }
  hsize_t n = value.size();
  Handle space(H5Screate_simple(1, &n, nullptr));
  write_attr(file_id_, object_path, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, space.get(),
             value.data(), [&](const std::string& what) { fail(object_path, what); });
}

void Writer::commit() {
  if (committed_) return;
  if (file_id_ < 0)
    fail("/", "file already closed");
  const herr_t closed = H5Fclose(file_id_);
  const std::string cause = closed < 0 ? hdf5_cause() : std::string();
  file_id_ = -1;
  if (closed < 0)
    fail("/", "cannot close the HDF5 file (" + cause + ")");
  const std::size_t size = image_size(*image_);
  if (size == 0)
    fail("/", "HDF5 left no file image to write");
  const auto* bytes = static_cast<const char*>(image_->data);
  for (std::size_t written = 0; written < size;) {
    const ssize_t n = ::write(tmp_fd_, bytes + written, size - written);
    if (n < 0 && errno == EINTR)
      continue;
    if (n <= 0) {
      throw InternalError(path_.string() + ": cannot write " + std::to_string(size) + " bytes to " +
                          tmp_path_.string() + " (" +
                          (n < 0 ? std::strerror(errno) : "nothing written") + ")");
    }
    written += static_cast<std::size_t>(n);
  }
  std::free(image_->data);
  image_->data = nullptr;
  const int fd = tmp_fd_;
  tmp_fd_ = -1;
  if (::close(fd) != 0) {  // where a network file system reports what did not fit
    throw InternalError(path_.string() + ": cannot write " + tmp_path_.string() + " (" +
                        std::strerror(errno) + ")");
  }
  std::error_code ec;
  std::filesystem::rename(tmp_path_, path_, ec);
  if (ec) {
    throw InternalError(path_.string() + ": cannot rename from " + tmp_path_.string() + ": " +
                        ec.message());
  }
  committed_ = true;
}

}  // namespace tfmb::h5
