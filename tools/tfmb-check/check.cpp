#include "check.hpp"

#include <algorithm>
#include <iomanip>
#include <limits>

#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/formats/files.hpp"
#include "tfmb/formats/schema.hpp"

namespace tfmb::check {
namespace {

std::string shape_text(const std::vector<std::size_t>& shape) {
  std::string text = "(";
  for (std::size_t i = 0; i < shape.size(); ++i) text += (i ? "," : "") + std::to_string(shape[i]);
  if (shape.size() == 1) text += ",";
  return text + ")";
}

void summarise(const h5::Reader& file, const formats::Schema& schema, std::ostream& out) {
  out << file.path().string() << ": " << schema.kind << " " << file.attr_string("/", "format_version")
      << " (" << schema.summary << ")\n";
  out << "  creator: " << file.attr_string("/", "creator") << "\n";
  if (file.has_attr("/", "geometry")) {
    out << "  geometry: " << file.attr_string("/", "geometry") << ", depth "
        << file.attr_f64("/", "depth") << " m\n";
  }
  if (file.is_dataset("/provenance/input_files")) {
    const auto inputs = file.read_strings("/provenance/input_files");
    std::vector<std::string> hashes;
    if (file.is_dataset("/provenance/input_sha256")) hashes = file.read_strings("/provenance/input_sha256");
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      out << "  input: " << inputs[i];
      if (i < hashes.size()) out << "  sha256 " << hashes[i].substr(0, 12);
      out << "\n";
    }
  }
  const formats::Document document = formats::read_document(file);
  for (const auto& [path, value] : document.datasets) {
    if (path.rfind("/provenance", 0) == 0) continue;
    std::string units;
    if (auto a = document.attributes.find(path); a != document.attributes.end()) {
      if (auto u = a->second.find("units"); u != a->second.end()) units = u->second.text;
    }
    out << "  " << std::left << std::setw(44) << path << " " << std::setw(8)
        << (value.dtype == h5::DType::float64 ? "float64"
                                              : value.dtype == h5::DType::int64 ? "int64" : "string")
        << std::setw(12) << shape_text(value.shape) << std::setw(10) << ("[" + units + "]");
    if (!value.floats.empty()) {
      const auto [lo, hi] = std::minmax_element(value.floats.begin(), value.floats.end());
      out << " min " << std::setprecision(6) << *lo << "  max " << *hi;
    } else if (!value.integers.empty()) {
      const auto [lo, hi] = std::minmax_element(value.integers.begin(), value.integers.end());
      out << " min " << *lo << "  max " << *hi;
    }
    out << std::right << "\n";
  }
}

}  // namespace

int check_files(const Options& options, std::ostream& out, std::ostream& err) {
  int status = 0;
  for (const auto& path : options.files) {
    try {
      h5::Reader file(path);
      const formats::Schema* schema = &formats::schema_of(file);
      const auto problems = formats::validate(file, *schema, false);
      for (const auto& problem : problems) err << problem.message << "\n";
      if (!problems.empty()) {
        status = 3;
        continue;
      }
      if (options.summary) summarise(file, *schema, out);
    } catch (const Error& e) {
      err << e.what() << "\n";
      status = 3;
    }
  }
  return status;
}

int run(const Options& options, std::ostream& out, std::ostream& err) {
  if (options.list_kinds) {
    for (const auto& schema : formats::all_schemas()) {
      out << std::left << std::setw(12) << schema.kind << " " << schema.format << " "
          << schema.version() << "  " << schema.summary << "\n";
    }
    return 0;
  }
  if (!options.spec_kind.empty()) {
    const auto* schema = formats::find_schema(options.spec_kind);
    if (!schema) throw UsageError("unknown kind '" + options.spec_kind + "' (see --list)");
    out << formats::markdown_table(*schema);
    return 0;
  }
  if (!options.example_kind.empty()) {
    const auto* schema = formats::find_schema(options.example_kind);
    if (!schema) throw UsageError("unknown kind '" + options.example_kind + "' (see --list)");
    if (options.output.empty()) throw UsageError("--example needs -o/--output");
    formats::write_document(formats::example_document(*schema), options.output);
    formats::write_xdmf_sidecar(options.output);
    return 0;
  }
  if (options.files.empty()) throw UsageError("no file given (see --help)");
  if (options.series && options.output.empty())
    throw UsageError("--series needs -o/--output");
  // A sidecar or series is written only over files that pass their checks, so that ParaView is
  // never pointed at a file the toolchain itself would refuse.
  const int status = check_files(options, out, err);
  if (status != 0)
    return status;
  if (options.sidecar) {
    for (const auto& file : options.files) {
      if (formats::write_xdmf_sidecar(file).empty())
        err << file.string() << ": no sidecar (nothing to draw in this kind)\n";
    }
  }
  if (options.series)
    formats::write_xdmf_series(options.output, options.files);
  return 0;
}

}  // namespace tfmb::check
