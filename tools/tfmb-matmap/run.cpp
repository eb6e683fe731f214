#include "run.hpp"

#include <algorithm>
#include <iomanip>
#include <set>
#include <sstream>

#include "section.hpp"
#include "tfmb/common/cli.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/text.hpp"
#include "thermal_strain.hpp"

namespace tfmb::matmap {

namespace {

// Evaluates properties of one element, collecting what had to be clamped.
struct ElementLookup {
  const Material& material;
  bool clamp;
  std::set<std::string> clamped;  // "<property> at <T> K"
  std::string location;           // for messages

  double operator()(const std::string& property, double t, const std::string& which) {
    const PropertyTable& table = material.require(property);
    try {
      const Evaluation e = evaluate(table, t, clamp);
      if (e.clamped)
        clamped.insert(property + " at " + which + " " + text::format_number(t) + " K [" +
                       text::format_number(table.lowest()) + ", " +
                       text::format_number(table.highest()) + "]");
      return e.value;
    } catch (const OutsideTable& e) {
      throw BadInput(location + ": " + which + " " + e.what() + " of " + material.name +
                     " (give --clamp to use the table's end value, flagged per element)");
    }
  }
};

}  // namespace

Result run(const Options& options, const Logger& logger, std::ostream& out) {
  const MaterialDatabase db = read_material_db(options.database_file);
  const Model model = read_model(options.model_file);
  const std::map<std::string, ThermalFlap> thermal = read_thermal(options.thermal_file);
  const std::string tfile = options.thermal_file.string();

  for (const auto& [name, flap] : thermal) {
    if (std::none_of(model.flaps.begin(), model.flaps.end(),
                     [&](const ModelFlap& f) { return f.name == name; })) {
      throw BadInput(tfile + ": /beam/" + name + ": flap not in " + options.model_file.string() +
                     " (mismatched model and thermal files)");
    }
  }
  Result result;
  // The table goes to `out` only when every flap mapped, so an error leaves stdout empty.
  std::ostringstream table;
  table << "tfmb-matmap: properties at the element temperatures (" << options.database_file.string()
        << ")\n";
  table << std::left << std::setw(12) << "flap" << std::setw(14) << "material" << std::right
        << std::setw(6) << "elems" << std::setw(18) << "T min..max [K]" << std::setw(20)
        << "E min..max [GPa]" << std::setw(14) << "eps_th max" << std::setw(14) << "allow. min"
        << std::setw(9) << "clamped"
        << "\n";
  for (const ModelFlap& mf : model.flaps) {
    auto it = thermal.find(mf.name);
    if (it == thermal.end()) {
      throw BadInput(tfile + ": /beam: no temperatures for flap '" + mf.name + "' of " +
                     options.model_file.string() + " (mismatched model and thermal files)");
    }
    const ThermalFlap& tf = it->second;
    const std::string location = tfile + ": /beam/" + mf.name + "/mean_temperature";
    if (tf.mean_temperature.size() != static_cast<std::size_t>(mf.elements)) {
      throw BadInput(location + ": " + std::to_string(tf.mean_temperature.size()) +
                     " elements, but flap '" + mf.name + "' of " + options.model_file.string() +
                     " has " + std::to_string(mf.elements) +
                     " (mismatched model and thermal files)");
    }
    const Material* material = db.find(mf.material);
    if (!material) {
      std::string names;
      for (const auto& m : db.materials)
        names += (names.empty() ? "" : ", ") + m.name;
      throw BadInput(options.model_file.string() + ": /flaps/" + mf.name + ": material '" +
                     mf.material + "' is not in " + options.database_file.string() +
                     " (materials: " + names + ")");
    }
    MaterialsFlap flap;
    flap.name = mf.name;
    flap.material = material->name;
    flap.material_given = mf.material;
    flap.thickness = mf.thickness;
    flap.width = mf.width;
    flap.outer_normal_sign = mf.outer_normal_sign;
    flap.reference_temperature = material->reference_temperature;
    flap.stress_free_temperature = options.stress_free_temperature.value_or(
        model.stress_free_temperature.value_or(material->reference_temperature));
    const bool has_nu = material->find("poisson_ratio") != nullptr;
    const bool has_g = material->find("shear_modulus") != nullptr;
    if ((!has_nu || !has_g) && !options.poisson_ratio) {
      throw BadInput(options.database_file.string() + ": /materials/" + material->name + ": no " +
                     (has_nu ? "shear_modulus" : "poisson_ratio") + " (missing: " +
                     material->missing + "); give --poisson-ratio to use G = E / (2 (1 + nu))");
    }
    flap.shear_modulus_basis =
        has_g && has_nu
            ? "material database"
            : "G = E / (2 (1 + nu)) with nu = " + text::format_number(*options.poisson_ratio) +
                  " (--poisson-ratio)";
    flap.has_strength = material->find("yield_strength") && material->find("ultimate_strength");
    if (!material->find("allowable_strain") && !options.allowable_strain) {
      throw BadInput(options.database_file.string() + ": /materials/" + material->name +
                     ": no allowable_strain (missing: " + material->missing +
                     "); give --allowable-strain to use a temperature-independent value");
    }
    flap.allowable_strain_basis =
        options.allowable_strain
            ? "temperature-independent value " + text::format_number(*options.allowable_strain) +
                  " (--allowable-strain)"
            : "material database: yield_strength / youngs_modulus at the element temperature";
    const RectangleSection section{mf.thickness, mf.width};
    ElementProperties& e = flap.elements;
    const double t_ref = material->reference_temperature;
    const double t0 = flap.stress_free_temperature;
    for (std::size_t k = 0; k < static_cast<std::size_t>(mf.elements); ++k) {
      const double t = tf.mean_temperature[k];
      const double dt = tf.delta_temperature[k];
      ElementLookup lookup{*material, options.clamp, {}, location + "[" + std::to_string(k) + "]"};
      const double E = lookup("youngs_modulus", t, "element temperature");
      const double nu =
          has_nu ? lookup("poisson_ratio", t, "element temperature") : *options.poisson_ratio;
      const double G = has_g && has_nu ? lookup("shear_modulus", t, "element temperature")
                                       : E / (2.0 * (1.0 + nu));
      const double alpha = lookup("thermal_expansion", t, "element temperature");
      const double alpha_in =
          lookup("thermal_expansion", t - 0.5 * dt, "inner surface temperature");
      const double alpha_out =
          lookup("thermal_expansion", t + 0.5 * dt, "outer surface temperature");
      lookup.location = options.stress_free_temperature
                            ? std::string("--stress-free-temperature")
                            : options.model_file.string() + ": /thermal@reference_temperature";
      const double alpha0 = lookup("thermal_expansion", t0, "stress-free temperature");
      lookup.location = location + "[" + std::to_string(k) + "]";
      const double rho = lookup("density", t, "element temperature");
      e.temperature.push_back(t);
      e.delta_temperature.push_back(dt);
      e.youngs_modulus.push_back(E);
      e.shear_modulus.push_back(G);
      e.poisson_ratio.push_back(nu);
      e.thermal_expansion.push_back(alpha);
      e.density.push_back(rho);
      if (flap.has_strength) {
        e.yield_strength.push_back(lookup("yield_strength", t, "element temperature"));
        e.ultimate_strength.push_back(lookup("ultimate_strength", t, "element temperature"));
      }
      e.allowable_strain.push_back(options.allowable_strain
                                       ? *options.allowable_strain
                                       : lookup("allowable_strain", t, "element temperature"));
      const double eps = thermal_strain(alpha, t, alpha0, t0, t_ref);
      const double eps_in = thermal_strain(alpha_in, t - 0.5 * dt, alpha0, t0, t_ref);
      const double eps_out = thermal_strain(alpha_out, t + 0.5 * dt, alpha0, t0, t_ref);
      e.thermal_strain.push_back(section_thermal_strain(eps_in, eps, eps_out));
      e.thermal_strain_inner.push_back(eps_in);
      e.thermal_strain_outer.push_back(eps_out);
      e.thermal_curvature.push_back(thermal_curvature(eps_out, eps_in, mf.thickness));
      e.section_stiffness.push_back(section_stiffness(section, E, G, nu));
      e.section_mass.push_back(section_mass(section, rho));
      e.clamped.push_back(lookup.clamped.empty() ? 0 : 1);
      if (!lookup.clamped.empty()) {
        std::string what;
        for (const auto& c : lookup.clamped)
          what += (what.empty() ? "" : "; ") + c;
        logger.warn("flap " + mf.name + " element " + std::to_string(k) +
                    ": clamped to the table end: " + what);
        ++result.clamped_elements;
      }
    }
    const auto [tmin, tmax] = std::minmax_element(e.temperature.begin(), e.temperature.end());
    const auto [emin, emax] = std::minmax_element(e.youngs_modulus.begin(), e.youngs_modulus.end());
    double eps_max = 0.0;
    for (double v : e.thermal_strain)
      eps_max = std::max(eps_max, std::abs(v));
    const double allow_min =
        *std::min_element(e.allowable_strain.begin(), e.allowable_strain.end());
    std::int64_t clamped = 0;
    for (auto c : e.clamped)
      clamped += c;
    table << std::left << std::setw(12) << mf.name << std::setw(14) << material->name << std::right
          << std::setw(6) << mf.elements << std::setw(18)
          << (text::format_number(*tmin) + ".." + text::format_number(*tmax)) << std::setw(20)
          << (text::format_number(*emin / 1e9) + ".." + text::format_number(*emax / 1e9))
          << std::setw(14) << std::setprecision(4) << eps_max << std::setw(14) << allow_min
          << std::setw(9) << clamped << "\n";
    result.flaps.push_back(std::move(flap));
  }
  out << table.str();
  formats::Header header = model.header;
  header.creator = "tfmb-matmap " + cli::version();
  formats::Provenance provenance;
  provenance.command_line = options.command_line;
  provenance.settings = options.settings_toml;
  provenance.inputs = {options.thermal_file, options.model_file, options.database_file};
  write_materials(options.output, header, result.flaps, provenance);
  logger.summary("wrote " + options.output.string() + ": " + std::to_string(result.flaps.size()) +
                 " flaps, " + std::to_string(result.clamped_elements) + " clamped elements");
  return result;
}

}  // namespace tfmb::matmap
