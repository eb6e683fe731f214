#include "case_file.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <toml++/toml.h>

#include "tfmb/common/cli.hpp"
#include "tfmb/common/errors.hpp"

namespace tfmb::input {
namespace {

std::string location(const std::filesystem::path& file, const toml::node* node) {
  std::string text = file.string();
  if (node && node->source().begin.line > 0) text += ":" + std::to_string(node->source().begin.line);
  return text;
}

// Strict access to one TOML table: every key read is remembered, finish() rejects the rest.
class Keys {
 public:
  Keys(const toml::table& table, std::string prefix, const std::filesystem::path& file)
      : table_(table), prefix_(std::move(prefix)), file_(file) {}

  bool has(const std::string& key) {
    used_.insert(key);
    return table_.contains(key);
  }
  std::string where(const std::string& key) const {
    return location(file_, table_.get(key) ? table_.get(key) : &table_) + ": " + prefix_ + key;
  }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw BadInput(where(key) + ": " + what);
  }

  double number(const std::string& key, std::optional<double> fallback, double lo, double hi,
                const std::string& units) {
    used_.insert(key);
    const toml::node* node = table_.get(key);
    if (!node) {
      if (!fallback) throw BadInput(location(file_, &table_) + ": missing key '" + prefix_ + key +
                                    "' [" + units + "]");
      return *fallback;
    }
    const auto value = node->value<double>();
    if (!value || !(node->is_floating_point() || node->is_integer())) fail(key, "expected a number [" + units + "]");
    if (!std::isfinite(*value) || *value < lo || *value > hi) {
      std::ostringstream what;
      what << "= " << *value << " outside the allowed range [" << lo << ", " << hi << "] " << units;
      fail(key, what.str());
    }
    return *value;
  }
  int integer(const std::string& key, std::optional<int> fallback, int lo, int hi) {
    used_.insert(key);
    const toml::node* node = table_.get(key);
    if (!node) {
      if (!fallback) throw BadInput(location(file_, &table_) + ": missing key '" + prefix_ + key + "'");
      return *fallback;
    }
    if (!node->is_integer()) fail(key, "expected an integer");
    const auto value = *node->value<std::int64_t>();
    if (value < lo || value > hi) {
      fail(key, "= " + std::to_string(value) + " outside the allowed range [" + std::to_string(lo) +
                    ", " + std::to_string(hi) + "]");
    }
    return static_cast<int>(value);
  }
  bool boolean(const std::string& key, bool fallback) {
    used_.insert(key);
    const toml::node* node = table_.get(key);
    if (!node) return fallback;
    if (!node->is_boolean()) fail(key, "expected true or false");
    return *node->value<bool>();
  }
  std::string text(const std::string& key, std::optional<std::string> fallback,
                   const std::vector<std::string>& allowed = {}) {
    used_.insert(key);
    const toml::node* node = table_.get(key);
    if (!node) {
      if (!fallback) throw BadInput(location(file_, &table_) + ": missing key '" + prefix_ + key + "'");
      return *fallback;
    }
    if (!node->is_string()) fail(key, "expected a string");
    std::string value = *node->value<std::string>();
    if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), value) == allowed.end()) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      fail(key, "= '" + value + "', expected one of: " + list);
    }
    return value;
  }
  std::vector<std::string> strings(const std::string& key) {
    used_.insert(key);
    const toml::array* array = table_.get_as<toml::array>(key);
    if (!array) {
      if (table_.get(key)) fail(key, "expected an array of strings");
      throw BadInput(location(file_, &table_) + ": missing key '" + prefix_ + key + "'");
    }
    std::vector<std::string> values;
    for (const auto& element : *array) {
      if (!element.is_string()) fail(key, "expected an array of strings");
      values.push_back(*element.value<std::string>());
    }
    return values;
  }
  // A numeric matrix written as an array of rows.
  // flat = true reads a single row written as a plain array ([x, y]).
  Eigen::MatrixXd matrix(const std::string& key, int rows, int cols, const std::string& units,
                         bool flat = false) {
    used_.insert(key);
    const toml::array* given = table_.get_as<toml::array>(key);
    if (!given) fail(key, "expected an array of rows [" + units + "]");
    toml::array wrapped;
    if (flat) wrapped.push_back(*given);
    const toml::array* array = flat ? &wrapped : given;
    if (rows > 0 && static_cast<int>(array->size()) != rows) {
      fail(key, "has " + std::to_string(array->size()) + " rows, expected " + std::to_string(rows));
    }
    Eigen::MatrixXd m(static_cast<Eigen::Index>(array->size()), cols);
    for (std::size_t r = 0; r < array->size(); ++r) {
      const toml::array* row = (*array)[r].as_array();
      if (!row || static_cast<int>(row->size()) != cols) {
        fail(key, "row " + std::to_string(r + 1) + " must hold " + std::to_string(cols) + " numbers");
      }
      for (int c = 0; c < cols; ++c) {
        const auto v = (*row)[static_cast<std::size_t>(c)].value<double>();
        if (!v || !std::isfinite(*v)) fail(key, "row " + std::to_string(r + 1) + " holds a non-number");
        m(static_cast<Eigen::Index>(r), c) = *v;
      }
    }
    return m;
  }
  const toml::table* table(const std::string& key) {
    used_.insert(key);
    const toml::node* node = table_.get(key);
    if (node && !node->is_table()) fail(key, "expected a table");
    return node ? node->as_table() : nullptr;
  }
  const toml::array* array_of_tables(const std::string& key) {
    used_.insert(key);
    const toml::node* node = table_.get(key);
    if (!node) return nullptr;
    const toml::array* array = node->as_array();
    if (!array || !array->is_array_of_tables()) fail(key, "expected [[" + key + "]] tables");
    return array;
  }
  void finish() const {
    for (const auto& [key, node] : table_) {
      const std::string name(key.str());
      if (used_.count(name)) continue;
      std::string allowed;
      for (const auto& k : used_) allowed += (allowed.empty() ? "" : ", ") + k;
      throw BadInput(location(file_, &node) + ": unknown key '" + prefix_ + name +
                     "' (allowed here: " + allowed + ")");
    }
  }

 private:
  const toml::table& table_;
  std::string prefix_;
  std::filesystem::path file_;
  std::set<std::string> used_;
};

constexpr double kInf = 1e300;

Matrix6 to_matrix6(const Eigen::MatrixXd& m) { return Matrix6(m); }

void read_section(Keys& keys, FlapSpec& spec) {
  Section& s = spec.flap.section;
  s.kind = keys.text("section", std::string("rectangle"), {"rectangle", "explicit"});
  if (s.kind == "rectangle") {
    s.youngs_modulus = keys.number("youngs_modulus", std::nullopt, 1e6, 1e13, "Pa");
    s.poisson_ratio = keys.number("poisson_ratio", 0.3, 0.0, 0.499, "1");
    s.density = keys.number("density", std::nullopt, 1.0, 1e5, "kg/m^3");
  } else {
    s.stiffness = to_matrix6(keys.matrix("stiffness", 6, 6, "N, N m^2"));
    s.mass = to_matrix6(keys.matrix("mass", 6, 6, "kg/m, kg m"));
    if ((s.stiffness - s.stiffness.transpose()).norm() > 1e-9 * s.stiffness.norm()) {
      keys.fail("stiffness", "the 6x6 section stiffness must be symmetric");
    }
    for (int i = 0; i < 6; ++i) {
      if (s.stiffness(i, i) <= 0.0) keys.fail("stiffness", "diagonal entries must be positive");
    }
  }
}

FlapSpec read_flap(const toml::table& table, int index, const std::filesystem::path& file) {
  FlapSpec spec;
  spec.line = static_cast<int>(table.source().begin.line);
  Keys keys(table, "flap[" + std::to_string(index) + "].", file);
  Flap& f = spec.flap;
  f.name = keys.text("name", std::nullopt);
  f.curves = keys.strings("curves");
  if (f.curves.empty()) keys.fail("curves", "needs at least one geometry curve");
  f.half = keys.text("half", std::string("none"), {"upper", "lower", "none"});
  spec.reference = keys.text("reference", std::string("mid"), {"mid", "inner", "outer"});
  f.thickness = keys.number("thickness", std::nullopt, 1e-5, 1.0, "m");
  f.width = keys.number("width", 1.0, 1e-4, 100.0, "m");
  f.material = keys.text("material", std::nullopt);
  f.elements = keys.integer("elements", 10, 1, 10000);
  read_section(keys, spec);
  keys.finish();
  return spec;
}

JointSpec read_joint(const toml::table& table, int index, const std::filesystem::path& file) {
  JointSpec spec;
  spec.line = static_cast<int>(table.source().begin.line);
  Keys keys(table, "joint[" + std::to_string(index) + "].", file);
  Joint& j = spec.joint;
  j.name = keys.text("name", std::nullopt);
  j.kind = keys.text("kind", std::nullopt,
                     {"rigid", "revolute", "revolute_spring", "revolute_clearance", "flexible",
                      "prescribed_rotation", "prismatic"});
  const auto flaps = keys.strings("flaps");
  if (flaps.size() != 2) keys.fail("flaps", "a joint connects exactly two flaps");
  j.flap_a = flaps[0];
  j.flap_b = flaps[1];
  if (keys.has("point")) {
    const Eigen::MatrixXd p = keys.matrix("point", 1, 2, "m", true);
    spec.point = Point(p(0, 0), p(0, 1));
  }
  if (j.kind == "revolute_spring") {
    j.stiffness = keys.number("stiffness", std::nullopt, 0.0, kInf, "N m/rad");
    j.damping = keys.number("damping", 0.0, 0.0, kInf, "N m s/rad");
  } else if (j.kind == "revolute_clearance") {
    j.inner_radius = keys.number("inner_radius", std::nullopt, 1e-6, 1.0, "m");
    j.outer_radius = keys.number("outer_radius", std::nullopt, 1e-6, 1.0, "m");
    if (j.outer_radius <= j.inner_radius) keys.fail("outer_radius", "must exceed inner_radius");
    j.contact_stiffness = keys.number("contact_stiffness", 1e8, 0.0, kInf, "N/m");
    j.friction = keys.number("friction", 0.0, 0.0, 1.0, "1");
  } else if (j.kind == "flexible") {
    j.stiffness_matrix = to_matrix6(keys.matrix("stiffness_matrix", 6, 6, "N/m, N m/rad"));
    j.deformation_measure = keys.text("deformation_measure", std::string("proposed"),
                                      {"proposed", "typical"});
    std::vector<std::string> names{"default", "custom"};
    for (char r = '1'; r <= '4'; ++r)
      for (char c = 'a'; c <= 'd'; ++c) names.push_back(std::string{r, c});
    j.measure_functions = keys.text("measure_functions", std::string("default"), names);
    if (j.measure_functions == "custom") {
      // Polynomial terms [coefficient, power of sigma, power of |p|]; the seed's small-motion
      // limits (its eqs. 18, 19): mu -> 1 and lambda -> 0, i.e. the constant terms sum to 1 and 0.
      auto terms = [&](const char* key, double limit, const char* why) {
        const Eigen::MatrixXd t = keys.has(key) ? keys.matrix(key, 0, 3, "1, 1, 1") : Eigen::MatrixXd(0, 3);
        double constant = 0.0;
        for (Eigen::Index r = 0; r < t.rows(); ++r) {
          for (int c : {1, 2})
            if (!(t(r, c) >= 0.0) || t(r, c) != std::floor(t(r, c)))
              keys.fail(key, "row " + std::to_string(r) + ": powers must be integers >= 0");
          if (static_cast<long>(t(r, 2)) % 2 != 0)
            keys.fail(key, "row " + std::to_string(r) + ": odd power of |p| is not differentiable at zero rotation; use even powers");
          if (t(r, 1) == 0.0 && t(r, 2) == 0.0) constant += t(r, 0);
        }
        if (std::abs(constant - limit) > 1e-12)
          keys.fail(key, "tends to " + std::to_string(constant) + " for small motion; " + why);
        return Eigen::MatrixX3d(t);
      };
      j.lambda_terms = terms("measure_lambda_terms", 0.0, "the seed's eq. (19) requires lambda -> 0");
      j.mu_terms = terms("measure_mu_terms", 1.0, "the seed's eq. (18) requires mu -> 1");
    }
  } else if (j.kind == "prismatic") {
    const Eigen::MatrixXd a = keys.matrix("axis", 1, 2, "1", true);
    const Point axis(a(0, 0), a(0, 1));
    if (!(axis.norm() > 1e-12)) keys.fail("axis", "the sliding direction has zero length");
    j.axis = axis.normalized();
  } else if (j.kind == "prescribed_rotation") {
    const Eigen::MatrixXd table_rows = keys.matrix("rotation", 0, 2, "s, rad");
    if (table_rows.rows() < 1) keys.fail("rotation", "needs at least one [time, angle] row");
    for (Eigen::Index r = 1; r < table_rows.rows(); ++r) {
      if (table_rows(r, 0) <= table_rows(r - 1, 0)) keys.fail("rotation", "times must increase");
    }
    j.rotation_table = table_rows;
  }
  keys.finish();
  return spec;
}

// The name of a [[support]] without one.
std::string default_support_name(const std::string& flap, const std::string& end) {
  return flap + "_" + end;
}

SupportSpec read_support(const toml::table& table, int index, const std::filesystem::path& file) {
  SupportSpec spec;
  spec.line = static_cast<int>(table.source().begin.line);
  Keys keys(table, "support[" + std::to_string(index) + "].", file);
  Support& s = spec.support;
  s.flap = keys.text("flap", std::nullopt);
  s.end = keys.text("end", std::nullopt, {"start", "end"});
  s.kind = keys.text("kind", std::string("clamp"),
                     {"clamp", "pinned", "sliding_clamp", "sliding_pinned"});
  if (s.slides() && keys.has("axis")) {
    const Eigen::MatrixXd a = keys.matrix("axis", 1, 2, "1", true);
    const Point axis(a(0, 0), a(0, 1));
    if (!(axis.norm() > 1e-12))
      keys.fail("axis", "the sliding direction has zero length");
    s.axis = axis.normalized();
  }
  s.name = keys.text("name", default_support_name(s.flap, s.end));
  keys.finish();
  return spec;
}

// Applies one --set override to the parsed document.
void apply_override(toml::table& root, const std::string& assignment) {
  auto [key, text] = cli::split_override(assignment);
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + text);
  } catch (const toml::parse_error&) {
    parsed = toml::table{{"v", text}};  // a bare word is taken as a string
  }
  std::vector<std::string> parts;
  std::stringstream stream(key);
  for (std::string part; std::getline(stream, part, '.');) parts.push_back(part);
  if (parts.empty()) throw UsageError("--set '" + assignment + "': empty key");
  toml::table* table = &root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    toml::node* node = table->get(parts[i]);
    if (node && node->is_array_of_tables() && i + 2 < parts.size()) {
      toml::table* found = nullptr;
      for (auto& element : *node->as_array()) {
        auto* t = element.as_table();
        auto name = t ? (*t)["name"].value<std::string>() : std::nullopt;
        const auto flap = t ? (*t)["flap"].value<std::string>() : std::nullopt;
        const auto end = t ? (*t)["end"].value<std::string>() : std::nullopt;
        if (!name && parts[i] == "support" && flap && end) name = default_support_name(*flap, *end);
        if (name == parts[i + 1]) {
          found = t;
        }
      }
      if (!found) throw UsageError("--set '" + assignment + "': no [[" + parts[i] + "]] named '" +
                                   parts[i + 1] + "'");
      table = found;
      ++i;
      continue;
    }
    if (!node) {
      table->insert(parts[i], toml::table{});
      node = table->get(parts[i]);
    }
    if (!node->is_table()) throw UsageError("--set '" + assignment + "': '" + parts[i] + "' is not a table");
    table = node->as_table();
  }
  table->insert_or_assign(parts.back(), *parsed.get("v"));
}

}  // namespace

CaseSpec read_case(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  if (!std::filesystem::exists(file)) throw BadInput(file.string() + ": case file not found");
  toml::table root;
  try {
    root = toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    throw BadInput(file.string() + ":" + std::to_string(e.source().begin.line) + ": " +
                   std::string(e.description()));
  }
  for (const auto& o : overrides) apply_override(root, o);
  CaseSpec spec;
  spec.file = file;
  {
    std::ostringstream text;
    text << root;
    spec.resolved_toml = text.str();
  }
  Keys top(root, "", file);
  Model& m = spec.settings;
  m.title = top.text("title", std::string(""));
  m.depth = top.number("depth", 1.0, 1e-6, 1e3, "m");

  if (const toml::table* t = top.table("geometry")) {
    Keys k(*t, "geometry.", file);
    const std::filesystem::path given = k.text("file", std::nullopt);
    spec.geometry.file = given.is_absolute() ? given : file.parent_path() / given;
    spec.geometry.scale = k.number("scale", 1.0, 1e-9, 1e9, "m per geometry unit");
    spec.geometry.tolerance = k.number("tolerance", 1e-6, 0.0, 1.0, "m");
    spec.geometry.curve_samples = k.integer("curve_samples", 64, 2, 100000);
    k.finish();
  }
  if (const toml::array* a = top.array_of_tables("flap")) {
    int i = 0;
    for (const auto& node : *a) spec.flaps.push_back(read_flap(*node.as_table(), i++, file));
  }
  if (const toml::array* a = top.array_of_tables("joint")) {
    int i = 0;
    for (const auto& node : *a) spec.joints.push_back(read_joint(*node.as_table(), i++, file));
  }
  if (const toml::array* a = top.array_of_tables("support")) {
    int i = 0;
    for (const auto& node : *a) spec.supports.push_back(read_support(*node.as_table(), i++, file));
  }
  {
    // Joints and supports share /joints of structure.h5 (their reactions), so their names must
    // differ from each other.
    std::map<std::string, int> seen;  // name -> line
    auto claim = [&](const std::string& name, int line, const char* what) {
      const auto [it, fresh] = seen.emplace(name, line);
      if (!fresh)
        throw BadInput(file.string() + ":" + std::to_string(line) + ": " + what + " name '" + name +
                       "' is already used on line " + std::to_string(it->second) +
                       " (joints and supports need distinct names)");
    };
    for (const JointSpec& j : spec.joints) claim(j.joint.name, j.line, "joint");
    for (const SupportSpec& s : spec.supports) claim(s.support.name, s.line, "support");
  }
  {
    static const toml::table empty;
    const toml::table* t = top.table("domain");
    Keys k(t ? *t : empty, "domain.", file);
    DomainSettings& d = m.domain.settings;
    d.kind = k.text("kind", std::string("nozzle"), {"nozzle", "channel", "flatplate", "none"});
    if (d.kind == "nozzle") {
      d.plenum_length = k.number("plenum_length", std::nullopt, 1e-6, 1e3, "m");
      d.downstream_length = k.number("downstream_length", std::nullopt, 1e-6, 1e4, "m");
      d.farfield_height = k.number("farfield_height", std::nullopt, 1e-6, 1e4, "m");
      d.boattail = k.boolean("boattail", false);
    } else if (d.kind == "channel") {
      d.wall_curve = k.text("wall_curve", std::nullopt);
    } else if (d.kind == "flatplate") {
      d.plate_length = k.number("plate_length", std::nullopt, 1e-6, 1e4, "m");
      d.upstream_length = k.number("upstream_length", std::nullopt, 0.0, 1e4, "m");
      d.farfield_height = k.number("height", std::nullopt, 1e-6, 1e4, "m");
    }
    m.geometry = k.text("geometry", std::string("planar"), {"planar", "axisymmetric"});
    // Only the channel has a line that can be the axis: its lower boundary y = 0. The nozzle
    // domain holds both halves and the flat plate lies on y = 0, so neither can turn about x.
    if (m.geometry == "axisymmetric" && d.kind != "channel") {
      k.fail("geometry",
             "= 'axisymmetric' needs domain.kind = 'channel' (the lower boundary y = 0 becomes "
             "the axis), not '" +
                 d.kind + "'");
    }
    // A body of revolution has no depth to refer quantities to (flowmesh.md: depth 1).
    if (m.geometry == "axisymmetric" && m.depth != 1.0) {
      k.fail("geometry",
             "= 'axisymmetric' needs the top-level depth = 1 (a body of revolution has no depth), "
             "not " +
                 std::to_string(m.depth));
    }
    k.finish();
  }
  {
    static const toml::table empty;
    const toml::table* t = top.table("flow");
    Keys k(t ? *t : empty, "flow.", file);
    FlowConditions& f = m.flow;
    f.nozzle_pressure_ratio = k.number("nozzle_pressure_ratio", 2.0, 1.0, 1000.0, "1");
    f.stagnation_temperature = k.number("stagnation_temperature", 294.0, 1.0, 5000.0, "K");
    f.ambient_pressure = k.number("ambient_pressure", 101325.0, 1.0, 1e10, "Pa");
    f.ambient_temperature = k.number("ambient_temperature", 288.15, 1.0, 5000.0, "K");
    f.ambient_mach = k.number("ambient_mach", 0.0, 0.0, 10.0, "1");
    f.exit_pressure_ratio = k.number("exit_pressure_ratio", 0.0, 0.0, 1.0, "1");
    f.gamma = k.number("gamma", 1.4, 1.01, 2.0, "1");
    f.gas_constant = k.number("gas_constant", 287.05, 1.0, 1e5, "J/(kg K)");
    f.prandtl = k.number("prandtl", 0.72, 0.01, 100.0, "1");
    f.turbulent_prandtl = k.number("turbulent_prandtl", 0.9, 0.01, 100.0, "1");
    f.turbulence =
        k.text("turbulence", std::string("spalart_allmaras"),
               {"spalart_allmaras", "k_omega_sst", "k_omega_sst_v", "laminar", "inviscid"});
    f.reference_length = k.number("reference_length", 0.0, 0.0, 1e4, "m");
    const bool has_height = k.has("first_cell_height");
    const bool has_yplus = k.has("yplus_target");
    if (has_height && has_yplus) k.fail("yplus_target", "give first_cell_height or yplus_target, not both");
    if (has_height) f.first_cell_height = k.number("first_cell_height", std::nullopt, 1e-12, 1.0, "m");
    if (has_yplus) f.yplus_target = k.number("yplus_target", std::nullopt, 1e-3, 1e4, "1");
    if (!has_height && !has_yplus) f.yplus_target = 1.0;
    k.finish();
  }
  {
    static const toml::table empty;
    const toml::table* t = top.table("thermal");
    Keys k(t ? *t : empty, "thermal.", file);
    ThermalSettings& th = m.thermal;
    th.flow_wall = k.text("flow_wall", std::string("adiabatic"), {"adiabatic", "isothermal"});
    th.wall_temperature = k.number("wall_temperature", th.flow_wall == "isothermal" ? std::nullopt
                                                                                    : std::optional<double>(0.0),
                                   0.0, 5000.0, "K");
    th.solid_boundary = k.text("solid_boundary", std::string("wall_temperature"),
                               {"wall_temperature", "convection", "convection_radiation"});
    th.emissivity = k.number("emissivity", 0.0, 0.0, 1.0, "1");
    th.reference_temperature = k.number("reference_temperature", 294.26, 1.0, 5000.0, "K");
    k.finish();
  }
  {
    static const toml::table empty;
    const toml::table* t = top.table("mesh");
    Keys k(t ? *t : empty, "mesh.", file);
    MeshControls& mc = m.mesh;
    mc.wall_size = k.number("wall_size", 0.0, 0.0, 1e3, "m");
    mc.far_size = k.number("far_size", 0.0, 0.0, 1e4, "m");
    mc.growth = k.number("growth", 1.2, 1.0, 3.0, "1");
    mc.max_layers = k.integer("max_layers", 40, 0, 200);
    mc.scale = k.number("scale", 1.0, 0.01, 100.0, "1");
    mc.cells_along = k.integer("cells_along", 0, 0, 100000);
    mc.cells_across = k.integer("cells_across", 0, 0, 100000);
    mc.cells_upstream = k.integer("cells_upstream", 0, 0, 100000);
    mc.leading_edge_spacing = k.number("leading_edge_spacing", 0.0, 0.0, 1e3, "m");
    mc.cells_per_circle = k.integer("cells_per_circle", 0, 0, 100000);
    mc.end_cells = k.integer("end_cells", 2, 2, 1000);
    mc.solid_cells_per_element = k.integer("solid_cells_per_element", 4, 1, 1000);
    mc.solid_layers = k.integer("solid_layers", 4, 1, 1000);
    if (k.has("first_layer_height")) {
      m.flow.first_cell_height = k.number("first_layer_height", std::nullopt, 1e-12, 1.0, "m");
      m.flow.yplus_target = 0.0;
    }
    k.finish();
  }
  {
    static const toml::table empty;
    const toml::table* t = top.table("analysis");
    Keys k(t ? *t : empty, "analysis.", file);
    AnalysisSettings& a = m.analysis;
    a.kind = k.text("kind", std::string("oneway"), {"oneway", "twoway", "structure", "flow"});
    a.time = k.text("time", std::string("static"), {"static", "dynamic"});
    a.end_time = k.number("end_time", 0.0, 0.0, 1e6, "s");
    a.time_step = k.number("time_step", 0.0, 0.0, 1e6, "s");
    if (a.time == "dynamic" && (a.end_time <= 0.0 || a.time_step <= 0.0)) {
      k.fail("time", "dynamic analysis needs end_time > 0 and time_step > 0");
    }
    a.load_steps = k.integer("load_steps", 10, 1, 100000);
    a.max_coupling_iterations = k.integer("max_coupling_iterations", 20, 1, 10000);
    a.coupling_tolerance = k.number("coupling_tolerance", 1e-4, 0.0, 1.0, "m");
    a.convergence = k.text("convergence", std::string("absolute"),
                           {"absolute", "relative", "residual-relative"});
    a.acceleration = k.text("acceleration", std::string("aitken"), {"constant", "aitken", "iqn-ils"});
    a.relaxation = k.number("relaxation", 0.5, 1e-6, 1.0, "1");
    k.finish();
  }
  top.finish();
  return spec;
}

namespace {
// Reference state for wall-spacing estimates: isentropic expansion from stagnation to the
// ambient pressure, capped at sonic (a choked nozzle's throat). Anderson (2003) eqs. 3.28-3.30.
struct ReferenceState {
  double density, velocity, viscosity;
};
ReferenceState reference_state(const FlowConditions& f) {
  const double g = f.gamma;
  const double pr = std::max(f.nozzle_pressure_ratio, 1.0 + 1e-9);
  double mach2 = 2.0 / (g - 1.0) * (std::pow(pr, (g - 1.0) / g) - 1.0);
  mach2 = std::min(mach2, 1.0);
  if (f.ambient_mach > 0.0) mach2 = f.ambient_mach * f.ambient_mach;
  const double t = f.stagnation_temperature / (1.0 + 0.5 * (g - 1.0) * mach2);
  const double p0 = f.nozzle_pressure_ratio * f.ambient_pressure;
  const double p = p0 * std::pow(1.0 + 0.5 * (g - 1.0) * mach2, -g / (g - 1.0));
  const double rho = p / (f.gas_constant * t);
  const double u = std::sqrt(mach2 * g * f.gas_constant * t);
  // Sutherland's law for air: White (2006) eq. 1-36, mu_ref 1.716e-5 Pa s at 273.15 K, S = 110.4 K.
  const double mu = 1.716e-5 * std::pow(t / 273.15, 1.5) * (273.15 + 110.4) / (t + 110.4);
  return {rho, u, mu};
}
// Friction velocity from the Schlichting flat-plate skin friction at x = reference length,
// Cf = (2 log10 Re_x - 0.65)^-2.3 (Schlichting, Boundary-Layer Theory, 7th ed., eq. 21.16).
double friction_velocity(const FlowConditions& f, const ReferenceState& s) {
  const double length = f.reference_length > 0.0 ? f.reference_length : 0.1;
  const double re = std::max(s.density * s.velocity * length / s.viscosity, 1e3);
  const double cf = std::pow(2.0 * std::log10(re) - 0.65, -2.3);
  return s.velocity * std::sqrt(0.5 * cf);
}
}  // namespace

double viscous_length(const FlowConditions& flow) {
  const ReferenceState s = reference_state(flow);
  const double length = s.viscosity / (s.density * friction_velocity(flow, s));
  // Conditions without a flow (a structure-only case, T0 = 0) give no estimate, not a NaN.
  return std::isfinite(length) && length > 0.0 ? length : 0.0;
}

}  // namespace tfmb::input
