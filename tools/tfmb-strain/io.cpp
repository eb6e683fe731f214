#include "io.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/common/text_file.hpp"
#include "tfmb/formats/materials.hpp"
#include "tfmb/formats/schema.hpp"
#include "tfmb/formats/strain.hpp"
#include "tfmb/formats/structure.hpp"

namespace tfmb::strain {

Structure read_structure(const std::filesystem::path& file) {
  const formats::Structure in = formats::read_structure(file);
  Structure out;
  out.header = in.header;
  out.converged = in.converged;
  for (std::size_t k = 0; k < in.segments.size(); ++k) {
    std::array<double, 6> strain{}, force{};
    for (std::size_t c = 0; c < 6; ++c) {
      strain[c] = in.sectional_strain[k](static_cast<Eigen::Index>(c));
      force[c] = in.sectional_force[k](static_cast<Eigen::Index>(c));
    }
    out.sectional_strain.push_back(strain);
    out.sectional_force.push_back(force);
  }
  for (const formats::StructureFlap& f : in.flaps) {
    StructureFlap flap;
    flap.segments = f.segments;
    double length = 0.0;
    for (std::int64_t segment : f.segments) {
      const auto& [head, tail] = in.segments[static_cast<std::size_t>(segment)];
      const Eigen::Vector2d a = in.points[static_cast<std::size_t>(head)].head<2>();
      const Eigen::Vector2d b = in.points[static_cast<std::size_t>(tail)].head<2>();
      flap.segment_middle.push_back(0.5 * (a + b));
      flap.segment_arc_length.push_back(length + 0.5 * (b - a).norm());
      length += (b - a).norm();
    }
    out.flaps[f.name] = std::move(flap);
  }
  return out;
}

std::map<std::string, MaterialsFlap> read_materials(const std::filesystem::path& file) {
  std::map<std::string, MaterialsFlap> out;
  for (const formats::MaterialsFlap& in : formats::read_materials(file).flaps) {
    const formats::MaterialElements& e = in.elements;
    MaterialsFlap f;
    f.thickness = in.thickness;
    f.outer_normal_sign = in.outer_normal_sign;
    f.material = in.material;
    f.temperature = e.temperature;
    f.allowable_strain = e.allowable_strain;
    f.thermal_strain_inner = e.thermal_strain_inner;
    f.thermal_strain_outer = e.thermal_strain_outer;
    f.thermal_strain = e.thermal_strain;
    f.thermal_curvature = e.thermal_curvature;
    for (std::size_t k = 0; k < e.section_stiffness.size(); ++k) {
      const auto& stiffness = e.section_stiffness[k];
      f.axial_stiffness.push_back(stiffness(0, 0));
      f.bending_stiffness.push_back(stiffness(5, 5));
      // The surface strains put the surfaces at +-thickness/2 of a section whose EA and EI are
      // those of the rectangle thickness x width (formats/materials.md): the rectangle's own
      // thickness, sqrt(12 EI / EA), is the thickness. A thickness that is not (found by the
      // mutation suite: 1e300 m turned a failing margin into a passing one) is refused.
      const double section_thickness = std::sqrt(12.0 * stiffness(5, 5) / stiffness(0, 0));
      if (!(std::abs(section_thickness - in.thickness) <= 1e-6 * section_thickness)) {
        std::ostringstream what;
        what << file.string() << ": /flaps/" << in.name << "@thickness: " << in.thickness
             << " m, but the section stiffness of element " << k << " is that of a "
             << section_thickness << " m thick rectangle (sqrt(12 EI / EA))";
        throw BadInput(what.str());
      }
    }
    f.clamped = e.clamped;
    out[in.name] = std::move(f);
  }
  return out;
}

// The file's own type (formats/strain.hpp) from the result; basis_name gives the basis's word.
void write_strain(const std::filesystem::path& file, const formats::Header& header,
                  const StrainResult& r, const formats::Provenance& provenance) {
  formats::Strain out;
  out.header = header;
  out.mechanical_basis = basis_name(r.basis);
  out.worst_margin_total = r.worst_total.margin;
  out.worst_margin_mechanical = r.worst_mechanical.margin;
  out.worst_margin_thermal = r.worst_thermal.margin;
  out.worst_flap = r.worst_total.flap;
  out.worst_segment = static_cast<std::int64_t>(r.worst_total.segment);
  out.worst_surface = r.worst_total.surface;
  out.worst_position = r.worst_total.position;
  for (const FlapStrains& f : r.flaps) {
    formats::StrainFlap flap;
    flap.name = f.name;
    flap.element = f.element;
    flap.s = f.s;
    flap.position = f.position;
    for (const SectionStrains& x : f.strains) {
      flap.mechanical_inner.push_back(x.mechanical_inner);
      flap.mechanical_outer.push_back(x.mechanical_outer);
      flap.thermal_inner.push_back(x.thermal_inner);
      flap.thermal_outer.push_back(x.thermal_outer);
      flap.total_inner.push_back(x.total_inner);
      flap.total_outer.push_back(x.total_outer);
    }
    flap.allowable = f.allowable;
    flap.margin_mechanical = f.margin_mechanical;
    flap.margin_thermal = f.margin_thermal;
    flap.margin_total = f.margin_total;
    out.flaps.push_back(std::move(flap));
  }
  for (const Worst& x : r.worst_list) {
    formats::StrainWorst worst;
    worst.flap = x.flap;
    worst.surface = x.surface;
    worst.segment = static_cast<std::int64_t>(x.segment);
    worst.element = x.element;
    worst.s = x.s;
    worst.position = x.position;
    worst.total_strain = x.strain;
    worst.margin_total = x.margin;
    out.worst.push_back(std::move(worst));
  }
  formats::write_strain(file, out, provenance);
}

namespace {

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string json_number(double v) {
  std::ostringstream o;
  o << std::setprecision(10) << v;
  return o.str();
}

std::string json_worst(const Worst& w) {
  return "{\"flap\": " + json_string(w.flap) + ", \"segment\": " + std::to_string(w.segment) +
         ", \"element\": " + std::to_string(w.element) + ", \"surface\": " + json_string(w.surface) +
         ", \"s\": " + json_number(w.s) + ", \"x\": " + json_number(w.position.x()) +
         ", \"y\": " + json_number(w.position.y()) + ", \"strain\": " + json_number(w.strain) +
         ", \"allowable\": " + json_number(w.allowable) + ", \"margin\": " + json_number(w.margin) + "}";
}

}  // namespace

void write_summary_json(const std::filesystem::path& file, const StrainResult& r) {
  {
    std::ostringstream out;
    out << "{\n  \"format\": \"tfmb/strain-summary\",\n  \"mechanical_basis\": " << json_string(basis_name(r.basis))
        << ",\n  \"worst\": {\n    \"mechanical\": " << json_worst(r.worst_mechanical)
        << ",\n    \"thermal\": " << json_worst(r.worst_thermal) << ",\n    \"total\": " << json_worst(r.worst_total)
        << "\n  },\n  \"flaps\": {";
    for (std::size_t f = 0; f < r.flaps.size(); ++f) {
      const FlapStrains& flap = r.flaps[f];
      double mm = kMarginCap, mt = kMarginCap, mtot = kMarginCap, emax = 0.0;
      for (std::size_t k = 0; k < flap.s.size(); ++k) {
        mm = std::min(mm, flap.margin_mechanical[k]);
        mt = std::min(mt, flap.margin_thermal[k]);
        mtot = std::min(mtot, flap.margin_total[k]);
        emax = std::max({emax, std::abs(flap.strains[k].total_inner), std::abs(flap.strains[k].total_outer)});
      }
      out << (f ? "," : "") << "\n    " << json_string(flap.name) << ": {\"segments\": " << flap.s.size()
          << ", \"min_margin_mechanical\": " << json_number(mm) << ", \"min_margin_thermal\": " << json_number(mt)
          << ", \"min_margin_total\": " << json_number(mtot) << ", \"max_abs_total_strain\": " << json_number(emax)
          << "}";
    }
    out << "\n  },\n  \"lowest_total_margins\": [";
    for (std::size_t i = 0; i < r.worst_list.size(); ++i) {
      out << (i ? "," : "") << "\n    " << json_worst(r.worst_list[i]);
    }
    out << "\n  ]\n}\n";
    write_text_atomically(file, out.str());
  }
}

}  // namespace tfmb::strain
