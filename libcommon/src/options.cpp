#include "tfmb/common/options.hpp"

#include <charconv>
#include <cstdio>
#include <sstream>

#include "tfmb/common/assert.hpp"
#include "tfmb/common/cli.hpp"

namespace tfmb::cli {

CLI::Validator range(double min, double max) {
  const std::string bounds = detail::shortest_text(min) + " - " + detail::shortest_text(max);
  return CLI::Validator(
      [min, max, bounds](std::string& input) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(input, value))
          return "'" + input + "' is not a number";
        // written so that NaN is refused too
        if (!(value >= min && value <= max))
          return input + " is outside [" + bounds + "]";
        return {};
      },
      "[" + bounds + "]");
}

namespace detail {

std::string shortest_text(double value) {
  char buffer[32];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  TFMB_ASSERT(error == std::errc(), "to_chars needs more than " << sizeof buffer << " characters");
  return std::string(buffer, end);
}

}  // namespace detail

std::string toml_float(double value) {
  std::string text = detail::shortest_text(value);
  // TOML reads "5" as an integer; inf and nan are TOML floats as they are
  if (text.find_first_of(".ein") == std::string::npos)
    text += ".0";
  return text;
}

std::string toml_string(const std::string& text) {
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      quoted += '\\';
      quoted += c;
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\u%04x", static_cast<unsigned>(c));
      quoted += escape;
    } else {
      quoted += c;
    }
  }
  return quoted + "\"";
}

namespace {

// "-o,--output" -> "output", "--max-iterations" -> "max_iterations", "mesh" -> "mesh"
// (a long name first, else a short one, else the positional name).
std::string settings_key(const std::string& names) {
  std::vector<std::string> long_names, short_names, positional_names;
  std::stringstream list(names);
  for (std::string name; std::getline(list, name, ',');) {
    name = CLI::detail::trim_copy(name);
    if (name.rfind("--", 0) == 0)
      long_names.push_back(name.substr(2));
    else if (name.rfind("-", 0) == 0)
      short_names.push_back(name.substr(1));
    else if (!name.empty() && name[0] != '!')
      positional_names.push_back(name);
  }
  TFMB_ASSERT(!long_names.empty() || !short_names.empty() || !positional_names.empty(),
              "no option name in '" << names << "'");
  std::string key = !long_names.empty()    ? long_names.front()
                    : !short_names.empty() ? short_names.front()
                                           : positional_names.front();
  for (char& c : key) {
    if (c == '-')
      c = '_';
  }
  return key;
}

}  // namespace

std::string OptionTable::help_text(const std::string& unit, const std::string& help) {
  return unit.empty() ? help : "[" + unit + "] " + help;
}

void OptionTable::record(const std::string& names, const std::string& unit,
                         std::function<std::optional<std::string>()> value) {
  const std::string key = settings_key(names);
  for (const Entry& entry : entries_) {
    TFMB_ASSERT(entry.key != key,
                "two options of " << app_.get_name() << " are recorded as '" << key << "'");
  }
  entries_.push_back({key, unit, std::move(value)});
}

CLI::Option* OptionTable::add_flag(const std::string& names, bool& value, const std::string& help) {
  CLI::Option* option = app_.add_flag(names, value, value ? help + " (default: on)" : help);
  record(names, "", [&value] { return detail::toml_value(value); });
  return option;
}

CLI::Option* OptionTable::add_output(std::filesystem::path& output, const std::string& what) {
  CLI::Option* option = add_output_option(app_, output, what);
  record("--output", "", [&output] { return detail::toml_value(output); });
  return option;
}

CLI::Option* OptionTable::add_set(std::vector<std::string>& overrides) {
  CLI::Option* option = add_set_option(app_, overrides);
  record("--set", "", [&overrides] { return detail::toml_value(overrides); });
  return option;
}

std::string OptionTable::settings_toml() const {
  std::string toml;
  if (app_.get_parent() != nullptr)
    toml += "command = " + toml_string(app_.get_name()) + "\n";
  for (const Entry& entry : entries_) {
    const std::optional<std::string> value = entry.value();
    if (!value) {
      toml += "# " + entry.key + ": not set\n";
      continue;
    }
    toml += entry.key + " = " + *value;
    if (!entry.unit.empty())
      toml += "  # " + entry.unit;
    toml += "\n";
  }
  return toml;
}

}  // namespace tfmb::cli
