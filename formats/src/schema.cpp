#include "tfmb/formats/schema.hpp"

#include <algorithm>
#include <sstream>

#include "tfmb/common/errors.hpp"

namespace tfmb::formats {
namespace {

std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> parts;
  std::stringstream stream(path);
  std::string part;
  while (std::getline(stream, part, '/')) {
    if (!part.empty()) parts.push_back(part);
  }
  return parts;
}

struct Match {
  std::string path;
  std::vector<std::string> wildcard_names;
};

// Expands the "*" segments of a pattern against the file. With datasets_only_last, a "*" in the
// last segment matches datasets; elsewhere it matches groups. A literal last segment is kept
// whether or not it exists (the caller reports it missing).
std::vector<Match> expand(const h5::Reader& file, const std::string& pattern, bool any_last) {
  const auto parts = split_path(pattern);
  std::vector<Match> current{{"", {}}};
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const bool last = i + 1 == parts.size();
    std::vector<Match> next;
    for (const Match& m : current) {
      if (parts[i] != "*") {
        next.push_back({m.path + "/" + parts[i], m.wildcard_names});
        continue;
      }
      const std::string parent = m.path.empty() ? "/" : m.path;
      if (!file.is_group(parent)) continue;
      for (const std::string& child : file.children(parent)) {
        const std::string child_path = m.path + "/" + child;
        if (!last && !file.is_group(child_path)) continue;
        if (last && !any_last && !file.is_dataset(child_path)) continue;
        Match extended{child_path, m.wildcard_names};
        extended.wildcard_names.push_back(child);
        next.push_back(extended);
      }
    }
    current = std::move(next);
  }
  if (parts.empty()) return {{"/", {}}};
  return current;
}

std::string number_text(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

bool is_number(const std::string& text) {
  return !text.empty() && std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

class Symbols {
 public:
  std::string key(const std::string& symbol, const std::vector<std::string>& scope) const {
    if (!symbol.empty() && symbol[0] >= 'a' && symbol[0] <= 'z') {
      std::string k = symbol + "|";
      for (const auto& s : scope) k += s + "/";
      return k;
    }
    return symbol;
  }
  // Value of "A", "A+B", or a number; nullopt if a symbol is unbound.
  std::optional<std::size_t> evaluate(const std::string& expression,
                                      const std::vector<std::string>& scope) const {
    std::size_t total = 0;
    std::stringstream stream(expression);
    std::string term;
    while (std::getline(stream, term, '+')) {
      if (is_number(term)) {
        total += std::stoull(term);
        continue;
      }
      auto it = values_.find(key(term, scope));
      if (it == values_.end()) return std::nullopt;
      total += it->second;
    }
    return total;
  }
  void bind(const std::string& symbol, const std::vector<std::string>& scope, std::size_t value) {
    values_[key(symbol, scope)] = value;
  }

 private:
  std::map<std::string, std::size_t> values_;
};

std::string shape_to_text(const std::vector<std::size_t>& shape) {
  std::string text = "(";
  for (std::size_t i = 0; i < shape.size(); ++i) text += (i ? "," : "") + std::to_string(shape[i]);
  if (shape.size() == 1) text += ",";
  return text + ")";
}

std::string pattern_to_text(const std::vector<std::string>& shape) {
  std::string text = "(";
  for (std::size_t i = 0; i < shape.size(); ++i) {
    text += (i ? "," : "") + (shape[i] == "?" ? std::string("[k]") : shape[i]);
  }
  if (shape.size() == 1) text += ",";
  return text + ")";
}

const char* dtype_text(h5::DType dtype) {
  switch (dtype) {
    case h5::DType::float64: return "float64";
    case h5::DType::int64: return "int64";
    case h5::DType::string: return "string";
    default: return "other";
  }
}

const char* attr_type_text(AttrType type) {
  switch (type) {
    case AttrType::string: return "string";
    case AttrType::float64: return "float64";
    case AttrType::int64: return "int64";
    case AttrType::float64_vector: return "float64[]";
  }
  return "?";
}

// Checks the shape and binds new symbols; returns an empty string or what is wrong.
std::string check_shape(const std::vector<std::size_t>& actual, const DatasetRule& rule,
                        const std::vector<std::string>& scope, Symbols& symbols) {
  std::vector<std::string> pattern = rule.shape;
  const bool optional_last = !pattern.empty() && pattern.back() == "?";
  const std::size_t required_rank = optional_last ? pattern.size() - 1 : pattern.size();
  if (actual.size() != required_rank && !(optional_last && actual.size() == pattern.size())) {
    return "wrong shape " + shape_to_text(actual) + ", expected " + pattern_to_text(rule.shape);
  }
  for (std::size_t d = 0; d < actual.size(); ++d) {
    const std::string& extent = pattern[d];
    if (extent == "*" || extent == "?") continue;
    if (is_number(extent)) {
      if (actual[d] != std::stoull(extent)) {
        return "wrong shape " + shape_to_text(actual) + ", expected " + pattern_to_text(rule.shape);
      }
      continue;
    }
    const auto value = symbols.evaluate(extent, scope);
    if (value) {
      if (*value != actual[d]) {
        return "wrong shape " + shape_to_text(actual) + ", expected " +
               pattern_to_text(rule.shape) + " with " + extent + " = " + std::to_string(*value);
      }
    } else if (extent.find('+') == std::string::npos) {
      symbols.bind(extent, scope, actual[d]);
    }
  }
  return {};
}

void check_attribute(const h5::Reader& file, const AttributeRule& rule, const std::string& object,
                     std::vector<Problem>& problems) {
  auto add = [&](const std::string& what) {
    problems.push_back({object, file.path().string() + ": " + object + ": " + what});
  };
  if (!file.has_attr(object, rule.name)) {
    if (rule.required) {
      add("missing attribute '" + rule.name + "'");
    } else if (!rule.required_with.empty() && file.has_attr(object, rule.required_with)) {
      add("missing attribute '" + rule.name + "', required with attribute '" + rule.required_with +
          "'");
    }
    return;
  }
  try {
    switch (rule.type) {
      case AttrType::string: {
        const std::string value = file.attr_string(object, rule.name);
        if (!rule.allowed.empty() &&
            std::find(rule.allowed.begin(), rule.allowed.end(), value) == rule.allowed.end()) {
          std::string allowed;
          for (const auto& a : rule.allowed) allowed += (allowed.empty() ? "" : ", ") + a;
          add("attribute '" + rule.name + "' is '" + value + "', expected one of: " + allowed);
        }
        break;
      }
      case AttrType::float64:
      case AttrType::int64: {
        const double value = rule.type == AttrType::int64
                                 ? static_cast<double>(file.attr_i64(object, rule.name))
                                 : file.attr_f64(object, rule.name);
        if ((rule.minimum && value < *rule.minimum) || (rule.maximum && value > *rule.maximum)) {
          std::ostringstream what;
          what << "attribute '" << rule.name << "' = " << value << " outside ["
               << (rule.minimum ? number_text(*rule.minimum) : "-inf") << ", "
               << (rule.maximum ? number_text(*rule.maximum) : "inf") << "]";
          add(what.str());
        }
        break;
      }
      case AttrType::float64_vector: file.attr_f64_vector(object, rule.name); break;
    }
  } catch (const h5::DamagedFile&) {
    throw;  // one line: what follows the first damage would be its consequences
  } catch (const BadInput& e) {
    problems.push_back({object, e.what()});
  }
}

}  // namespace

const Schema& schema_of(const h5::Reader& file) {
  if (!file.has_attr("/", "format"))
    file.fail("/", "missing attribute 'format': not a tfmb file");
  const std::string format = file.attr_string("/", "format");
  const Schema* schema = find_schema(format);
  if (!schema)
    file.fail("/", "unknown format '" + format + "'");
  return *schema;
}

std::vector<Problem> validate(const h5::Reader& file, const Schema& schema, bool stop_at_first) {
  std::vector<Problem> problems;
  auto add = [&](const std::string& object, const std::string& what) {
    problems.push_back({object, file.path().string() + ": " + object + ": " + what});
  };
  auto done = [&] { return stop_at_first && !problems.empty(); };

  // Identification and version first: nothing else is meaningful if they are wrong.
  try {
    if (!file.has_attr("/", "format")) {
      add("/", "missing attribute 'format' (expected '" + schema.format + "'): not a tfmb file?");
      return problems;
    }
    const std::string format = file.attr_string("/", "format");
    if (format != schema.format) {
      add("/", "attribute 'format' is '" + format + "', expected '" + schema.format + "'");
      return problems;
    }
    if (!file.has_attr("/", "format_version")) {
      add("/", "missing attribute 'format_version'");
      return problems;
    }
    const std::string version = file.attr_string("/", "format_version");
    const auto dot = version.find('.');
    if (dot == std::string::npos || !is_number(version.substr(0, dot)) ||
        !is_number(version.substr(dot + 1))) {
      add("/", "attribute 'format_version' is '" + version + "', expected 'major.minor'");
      return problems;
    }
    // compared as digits: a major of more digits than an int holds is unknown, not an
    // internal error (std::stoi threw out_of_range: exit 4 instead of 3)
    std::string major = version.substr(0, dot);
    major.erase(0, std::min(major.find_first_not_of('0'), major.size() - 1));
    if (major != std::to_string(schema.major)) {
      add("/", "unknown major format_version " + version + " (this build reads " +
                   std::to_string(schema.major) + ".x); convert the file or update tfmb");
      return problems;
    }
  } catch (const h5::DamagedFile&) {
    throw;
  } catch (const BadInput& e) {
    problems.push_back({"/", e.what()});
    return problems;
  }

  for (const AttributeRule& rule : schema.attributes) {
    for (const Match& m : expand(file, rule.object_path, true)) {
      if (!file.exists(m.path)) {
        if (rule.required) add(m.path, "missing (needed for attribute '" + rule.name + "')");
      } else {
        check_attribute(file, rule, m.path, problems);
      }
      if (done()) return problems;
    }
  }

  Symbols symbols;
  for (const DatasetRule& rule : schema.datasets) {
    for (const Match& m : expand(file, rule.path, false)) {
      if (!file.exists(m.path)) {
        if (rule.required) add(m.path, "missing dataset");
        if (done()) return problems;
        continue;
      }
      try {
        if (!file.is_dataset(m.path)) {
          add(m.path, "is a group, expected a dataset");
          if (done()) return problems;
          continue;
        }
        const h5::DatasetInfo info = file.info(m.path);
        if (info.dtype != rule.dtype) {
          add(m.path, "wrong dtype " + info.dtype_name + ", expected " + dtype_text(rule.dtype));
          if (done()) return problems;
          continue;
        }
        const std::string shape_problem = check_shape(info.shape, rule, m.wildcard_names, symbols);
        if (!shape_problem.empty()) {
          add(m.path, shape_problem);
          if (done()) return problems;
          continue;
        }
        if (!file.has_attr(m.path, "units")) {
          add(m.path, "missing attribute 'units'");
        } else {
          const std::string units = file.attr_string(m.path, "units");
          if (rule.units != "*" && units != rule.units) {
            add(m.path, "units '" + units + "', expected '" + rule.units + "'");
          }
        }
        if (rule.dtype == h5::DType::float64) {
          file.read_f64(m.path);  // throws on NaN/Inf with the location
        } else if (rule.dtype == h5::DType::int64) {
          const auto values = file.read_i64(m.path);
          if (!rule.index_bound.empty()) {
            const auto bound = symbols.evaluate(rule.index_bound, m.wildcard_names);
            for (std::size_t i = 0; bound && i < values.size(); ++i) {
              if (values[i] < rule.index_lower || values[i] >= static_cast<std::int64_t>(*bound)) {
                add(m.path, "index " + std::to_string(values[i]) + " at flat index " +
                                std::to_string(i) + " out of range [" +
                                std::to_string(rule.index_lower) + ", " + rule.index_bound +
                                " = " + std::to_string(*bound) + ")");
                break;
              }
            }
          }
        } else if (rule.dtype == h5::DType::string) {
          file.read_strings(m.path);
        }
      } catch (const h5::DamagedFile&) {
        throw;
      } catch (const BadInput& e) {
        problems.push_back({m.path, e.what()});
      }
      if (done()) return problems;
    }
  }
  return problems;
}

h5::Reader open_checked(const std::filesystem::path& path, const std::string& kind) {
  const Schema* schema = find_schema(kind);
  if (!schema) throw InternalError("unknown file kind '" + kind + "'");
  h5::Reader file(path);
  const auto problems = validate(file, *schema, true);
  if (!problems.empty()) throw BadInput(problems.front().message);
  return file;
}

std::string markdown_table(const Schema& schema) {
  std::ostringstream out;
  out << "| object | attribute / dataset | dtype | shape | units | required | meaning |\n";
  out << "|---|---|---|---|---|---|---|\n";
  for (const AttributeRule& a : schema.attributes) {
    std::string meaning = a.meaning;
    if (!a.allowed.empty()) {
      std::string allowed;
      for (const auto& v : a.allowed) allowed += (allowed.empty() ? "" : ", ") + ("`" + v + "`");
      meaning += (meaning.empty() ? "" : "; ") + std::string("one of ") + allowed;
    }
    if (a.minimum || a.maximum) {
      std::ostringstream range;
      range << "range [" << (a.minimum ? number_text(*a.minimum) : "-inf") << ", "
            << (a.maximum ? number_text(*a.maximum) : "inf") << "]";
      meaning += (meaning.empty() ? "" : "; ") + range.str();
    }
    out << "| `" << a.object_path << "` | @" << a.name << " | " << attr_type_text(a.type)
        << " | scalar | " << (a.units.empty() ? "" : a.units) << " | "
        << (a.required                ? "yes"
            : a.required_with.empty() ? "no"
                                      : "with @" + a.required_with)
        << " | " << meaning << " |\n";
  }
  for (const DatasetRule& d : schema.datasets) {
    std::string meaning = d.meaning;
    if (!d.index_bound.empty()) {
      meaning += (meaning.empty() ? "" : "; ") + std::string("values in [") +
                 std::to_string(d.index_lower) + ", " + d.index_bound + ")";
    }
    out << "| `" << d.path << "` | dataset | " << dtype_text(d.dtype) << " | "
        << pattern_to_text(d.shape) << " | " << d.units << " | " << (d.required ? "yes" : "no")
        << " | " << meaning << " |\n";
  }
  return out.str();
}

const Schema* find_schema(const std::string& kind_or_format) {
  for (const Schema& schema : all_schemas()) {
    if (schema.kind == kind_or_format || schema.format == kind_or_format) return &schema;
  }
  return nullptr;
}

}  // namespace tfmb::formats
