// Declaring a tool's command-line options once (DESIGN.md §5): an OptionTable registers each
// option with CLI11, takes its default from the bound variable's value at declaration (the
// options struct's initialiser, or a tool's own value assigned before declaring), shows that
// default and the unit in --help, optionally range-checks the value, and after parsing writes
// the value of every declared option as TOML for the output file's /provenance@settings.
//
//   tfmb::cli::OptionTable table(app);
//   table.add("--max-iterations", options.max_iterations, "1", "iteration limit",
//             tfmb::cli::range(1, 1e9));
//   ... parse ...
//   options.settings_toml = table.settings_toml();
//
// --help then shows `--max-iterations INT:[1 - 1e+09]=500   [1] iteration limit`, and the TOML
// holds `max_iterations = 500  # 1`.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

namespace tfmb::cli {

// Refuses a value outside [min, max] (a usage error, exit 2). For integer and floating options
// alike, unlike CLI::Range, whose two bounds must have one type.
CLI::Validator range(double min, double max);

// TOML values as settings_toml() writes them, also for a run that appends what it resolved
// from its inputs to the settings (a `[resolved]` table after the options' keys).
//
// A TOML float: the shortest text that reads back as the same double, with ".0" appended where
// it would read as an integer (2e+05, 0.001, 300.0).
std::string toml_float(double value);
// A TOML basic string: quoted, with backslash, quote and control characters escaped.
std::string toml_string(const std::string& text);

namespace detail {

// The shortest decimal text that reads back as the same double (std::to_chars): 101325, 1e-08.
std::string shortest_text(double value);

template <typename T>
struct is_vector : std::false_type {};
template <typename T>
struct is_vector<std::vector<T>> : std::true_type {};
template <typename T>
struct is_optional : std::false_type {};
template <typename T>
struct is_optional<std::optional<T>> : std::true_type {};

// The value as --help shows it after TYPE= ("" shows no default).
template <typename T>
std::string shown_value(const T& value) {
  if constexpr (std::is_same_v<T, bool>) {
    return value ? "true" : "false";
  } else if constexpr (std::is_integral_v<T>) {
    return std::to_string(value);
  } else if constexpr (std::is_floating_point_v<T>) {
    return shortest_text(static_cast<double>(value));
  } else if constexpr (std::is_same_v<T, std::filesystem::path>) {
    return value.string();
  } else if constexpr (std::is_convertible_v<T, std::string>) {
    return std::string(value);
  } else if constexpr (is_optional<T>::value) {
    return value ? shown_value(*value) : std::string();
  } else if constexpr (is_vector<T>::value) {
    std::string text;
    for (const auto& item : value)
      text += (text.empty() ? "" : " ") + shown_value(item);
    return text;
  } else {
    static_assert(!sizeof(T), "OptionTable: no text form for this option type");
  }
}

// The value as a TOML value; std::nullopt for an optional that was not given.
template <typename T>
std::optional<std::string> toml_value(const T& value) {
  if constexpr (std::is_same_v<T, bool>) {
    return std::string(value ? "true" : "false");
  } else if constexpr (std::is_integral_v<T>) {
    return std::to_string(value);
  } else if constexpr (std::is_floating_point_v<T>) {
    return toml_float(static_cast<double>(value));
  } else if constexpr (std::is_same_v<T, std::filesystem::path>) {
    return toml_string(value.string());
  } else if constexpr (std::is_convertible_v<T, std::string>) {
    return toml_string(std::string(value));
  } else if constexpr (is_optional<T>::value) {
    if (!value)
      return std::nullopt;
    return toml_value(*value);
  } else if constexpr (is_vector<T>::value) {
    std::string text;
    for (const auto& item : value)
      text += (text.empty() ? "" : ", ") + *toml_value(item);
    return "[" + text + "]";
  } else {
    static_assert(!sizeof(T), "OptionTable: no TOML form for this option type");
  }
}

}  // namespace detail

// The options of one CLI::App (a tool, or one of its subcommands). It keeps references to the
// bound variables, so it must not outlive them; settings_toml() reads their values when called.
class OptionTable {
 public:
  explicit OptionTable(CLI::App& app) : app_(app) {}
  OptionTable(const OptionTable&) = delete;
  OptionTable& operator=(const OptionTable&) = delete;

  // Declares an option ("--name", "-x,--name") or, for a name without a leading '-', a
  // positional argument, bound to `value`. The default shown in --help is `value` now (set it
  // before declaring); an std::optional not set shows none, so `help` says what its absence
  // means. `unit` is the value's unit ("Pa", "deg", "1" for dimensionless numbers and counts, ""
  // for names, switches and files): it leads the help text in brackets and follows the value in
  // settings_toml(). `check` refuses other values with a usage error (exit 2). Returns the
  // CLI11 option for further modifiers (->required(), ->take_all(), ...).
  template <typename T>
  CLI::Option* add(const std::string& names, T& value, const std::string& unit,
                   const std::string& help, const std::optional<CLI::Validator>& check = {}) {
    CLI::Option* option = app_.add_option(names, value, help_text(unit, help));
    if (check)
      option->check(*check);
    if (const std::string shown = detail::shown_value(value); !shown.empty())
      option->default_str(shown);
    record(names, unit, [&value] { return detail::toml_value(value); });
    return option;
  }

  // A switch set by its presence ("--name", or "--name,!--no-name" to also clear it); the help
  // text says when it is on by default.
  CLI::Option* add_flag(const std::string& names, bool& value, const std::string& help);

  // The required -o/--output file (see add_output_option in cli.hpp).
  CLI::Option* add_output(std::filesystem::path& output, const std::string& what);

  // Repeatable --set key=value overrides of case.toml settings (see add_set_option in cli.hpp).
  CLI::Option* add_set(std::vector<std::string>& overrides);

  // Every option declared here, in declaration order, one `key = value` line each (the key is
  // the long name without dashes, '-' -> '_', or the positional's name; the unit, if any, as a
  // trailing comment) and `# key: not set` for an std::optional without a value. A
  // subcommand's table starts with `command = "<subcommand>"`. Call it after parsing; it reads
  // the variables' current values.
  std::string settings_toml() const;

  CLI::App& app() { return app_; }

 private:
  struct Entry {
    std::string key;
    std::string unit;
    std::function<std::optional<std::string>()> value;
  };
  static std::string help_text(const std::string& unit, const std::string& help);
  void record(const std::string& names, const std::string& unit,
              std::function<std::optional<std::string>()> value);

  CLI::App& app_;
  std::vector<Entry> entries_;
};

}  // namespace tfmb::cli
