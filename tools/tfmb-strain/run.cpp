#include "run.hpp"

#include <algorithm>
#include <iomanip>
#include <sstream>

#include "tfmb/common/cli.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/formats/files.hpp"

namespace tfmb::strain {

namespace {

Worst worst_of(const FlapStrains& f, std::size_t k, double inner, double outer, double margin) {
  Worst w;
  w.flap = f.name;
  w.segment = k;
  w.element = f.element[k];
  w.surface = std::abs(inner) >= std::abs(outer) ? "inner" : "outer";
  w.strain = std::abs(inner) >= std::abs(outer) ? inner : outer;
  w.s = f.s[k];
  w.position = f.position[k];
  w.allowable = f.allowable[k];
  w.margin = margin;
  return w;
}

std::string describe(const Worst& w) {
  std::ostringstream o;
  o << std::setprecision(4) << w.margin << " at flap " << w.flap << " segment " << w.segment
    << " (element " << w.element << "), " << w.surface << " surface, s = " << w.s
    << " m, (x, y) = (" << w.position.x() << ", " << w.position.y() << ") m, strain " << w.strain
    << " of allowable " << w.allowable;
  return o.str();
}

}  // namespace

StrainResult run(const Options& options, const Logger& logger, std::ostream& out) {
  const Structure structure = read_structure(options.structure_file);
  const std::map<std::string, MaterialsFlap> materials = read_materials(options.materials_file);
  const std::string sfile = options.structure_file.string();
  const std::string mfile = options.materials_file.string();
  if (!structure.converged)
    logger.warn(sfile + ": the beam solution is flagged unconverged");
  for (const auto& [name, flap] : structure.flaps) {
    if (!materials.count(name)) {
      throw BadInput(sfile + ": /flaps/" + name + ": flap not in " + mfile +
                     " (mismatched structure and materials files)");
    }
  }
  StrainResult result;
  result.basis = options.basis;
  std::vector<Worst> all;
  bool first = true;
  for (const auto& [name, material] : materials) {
    auto it = structure.flaps.find(name);
    if (it == structure.flaps.end()) {
      throw BadInput(sfile + ": /flaps: flap '" + name + "' of " + mfile +
                     " is missing (mismatched structure and materials files)");
    }
    const StructureFlap& sf = it->second;
    const std::size_t ne = material.temperature.size();
    const std::size_t ns = sf.segments.size();
    // A beam element of order p is written as p segments: each material element covers
    // ns / ne consecutive segments.
    if (ne == 0 || ns % ne != 0) {
      throw BadInput(sfile + ": /flaps/" + name + "/segments: " + std::to_string(ns) +
                     " segments do not divide into the " + std::to_string(ne) + " elements of " +
                     mfile + " (mismatched structure and materials files)");
    }
    const std::size_t per_element = ns / ne;
    FlapStrains f;
    f.name = name;
    for (std::size_t k = 0; k < ns; ++k) {
      const std::size_t e = k / per_element;
      const auto& strain = structure.sectional_strain[static_cast<std::size_t>(sf.segments[k])];
      const auto& force = structure.sectional_force[static_cast<std::size_t>(sf.segments[k])];
      SectionInput in;
      in.axial_strain = strain[0];
      in.curvature = strain[5];
      in.axial_force = force[0];
      in.bending_moment = force[5];
      in.axial_stiffness = material.axial_stiffness[e];
      in.bending_stiffness = material.bending_stiffness[e];
      in.thickness = material.thickness;
      in.outer_normal_sign = material.outer_normal_sign;
      in.thermal_inner = material.thermal_strain_inner[e];
      in.thermal_outer = material.thermal_strain_outer[e];
      in.thermal_section = material.thermal_strain[e];
      in.thermal_curvature = material.thermal_curvature[e];
      const SectionStrains s = section_strains(in, options.basis);
      const double allowable = material.allowable_strain[e];
      f.element.push_back(static_cast<std::int64_t>(e));
      f.s.push_back(sf.segment_arc_length[k]);
      f.position.push_back(sf.segment_middle[k]);
      f.strains.push_back(s);
      f.allowable.push_back(allowable);
      auto margin = [&](double a, double b) {
        return margin_of_safety(allowable, std::max(std::abs(a), std::abs(b)));
      };
      f.margin_mechanical.push_back(margin(s.mechanical_inner, s.mechanical_outer));
      f.margin_thermal.push_back(margin(s.thermal_inner, s.thermal_outer));
      f.margin_total.push_back(margin(s.total_inner, s.total_outer));
    }
    for (std::size_t k = 0; k < ns; ++k) {
      const SectionStrains& s = f.strains[k];
      const Worst m =
          worst_of(f, k, s.mechanical_inner, s.mechanical_outer, f.margin_mechanical[k]);
      const Worst t = worst_of(f, k, s.thermal_inner, s.thermal_outer, f.margin_thermal[k]);
      const Worst tot = worst_of(f, k, s.total_inner, s.total_outer, f.margin_total[k]);
      if (first || m.margin < result.worst_mechanical.margin)
        result.worst_mechanical = m;
      if (first || t.margin < result.worst_thermal.margin)
        result.worst_thermal = t;
      if (first || tot.margin < result.worst_total.margin)
        result.worst_total = tot;
      first = false;
      all.push_back(tot);
    }
    if (std::any_of(material.clamped.begin(), material.clamped.end(),
                    [](auto c) { return c != 0; })) {
      logger.warn("flap " + name + ": some elements had clamped material properties (see " + mfile +
                  ": /flaps/" + name + "/clamped)");
    }
    result.flaps.push_back(std::move(f));
  }
  std::stable_sort(all.begin(), all.end(),
                   [](const Worst& a, const Worst& b) { return a.margin < b.margin; });
  all.resize(std::min<std::size_t>(all.size(),
                                   static_cast<std::size_t>(std::max(options.worst_count, 1))));
  result.worst_list = all;

  out << "tfmb-strain: fibre strains and margins of safety (beam strain basis: "
      << basis_name(options.basis) << ")\n";
  out << std::left << std::setw(12) << "flap" << std::right << std::setw(9) << "segments"
      << std::setw(14) << "max|mech|" << std::setw(14) << "max|thermal|" << std::setw(14)
      << "max|total|" << std::setw(12) << "MS mech" << std::setw(12) << "MS thermal"
      << std::setw(12) << "MS total"
      << "\n";
  for (const FlapStrains& f : result.flaps) {
    double em = 0, et = 0, etot = 0, mm = kMarginCap, mt = kMarginCap, mtot = kMarginCap;
    for (std::size_t k = 0; k < f.s.size(); ++k) {
      const SectionStrains& s = f.strains[k];
      em = std::max({em, std::abs(s.mechanical_inner), std::abs(s.mechanical_outer)});
      et = std::max({et, std::abs(s.thermal_inner), std::abs(s.thermal_outer)});
      etot = std::max({etot, std::abs(s.total_inner), std::abs(s.total_outer)});
      mm = std::min(mm, f.margin_mechanical[k]);
      mt = std::min(mt, f.margin_thermal[k]);
      mtot = std::min(mtot, f.margin_total[k]);
    }
    out << std::left << std::setw(12) << f.name << std::right << std::setw(9) << f.s.size()
        << std::setprecision(4) << std::setw(14) << em << std::setw(14) << et << std::setw(14)
        << etot << std::setw(12) << mm << std::setw(12) << mt << std::setw(12) << mtot << "\n";
  }
  out << "worst mechanical margin: " << describe(result.worst_mechanical) << "\n";
  out << "worst thermal margin:    " << describe(result.worst_thermal) << "\n";
  out << "worst total margin:      " << describe(result.worst_total) << "\n";

  formats::Header header = structure.header;
  header.creator = "tfmb-strain " + cli::version();
  formats::Provenance provenance;
  provenance.command_line = options.command_line;
  provenance.settings = options.settings_toml;
  provenance.inputs = {options.structure_file, options.materials_file};
  write_strain(options.output, header, result, provenance);
  std::filesystem::path summary = options.summary;
  if (summary.empty())
    summary = options.output.parent_path() / "summary.json";
  try {
    write_summary_json(summary, result);
  } catch (...) {
    // the run's two results come together or not at all: no strain.h5 without its summary
    std::error_code ec;
    std::filesystem::path sidecar = options.output;
    std::filesystem::remove(sidecar.replace_extension(".xdmf"), ec);
    std::filesystem::remove(formats::meshio_sidecar_path(options.output), ec);
    std::filesystem::remove(options.output, ec);
    throw;
  }
  logger.summary("wrote " + options.output.string() + " and " + summary.string() +
                 "; worst total margin " + describe(result.worst_total));
  return result;
}

}  // namespace tfmb::strain
