#include "io.hpp"

#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/formats/materials.hpp"
#include "tfmb/formats/schema.hpp"
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
    for (const auto& k : e.section_stiffness) {
      f.axial_stiffness.push_back(k(0, 0));
      f.bending_stiffness.push_back(k(5, 5));
    }
    f.clamped = e.clamped;
    out[in.name] = std::move(f);
  }
  return out;
}

namespace {

h5::MatrixXdR positions(const std::vector<Eigen::Vector2d>& p) {
  h5::MatrixXdR m(static_cast<Eigen::Index>(p.size()), 2);
  for (std::size_t i = 0; i < p.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = p[i].transpose();
  return m;
}

}  // namespace

void write_strain(const std::filesystem::path& file, const formats::Header& header, const StrainResult& r,
                  const formats::Provenance& provenance) {
  h5::Writer w(file);
  formats::write_header(w, "strain", header);
  w.set_attr("/", "mechanical_basis", basis_name(r.basis));
  w.set_attr("/", "worst_margin_total", r.worst_total.margin);
  w.set_attr("/", "worst_margin_mechanical", r.worst_mechanical.margin);
  w.set_attr("/", "worst_margin_thermal", r.worst_thermal.margin);
  w.set_attr("/", "worst_flap", r.worst_total.flap);
  w.set_attr("/", "worst_segment", static_cast<std::int64_t>(r.worst_total.segment));
  w.set_attr("/", "worst_surface", r.worst_total.surface);
  w.set_attr("/", "worst_position", std::vector<double>{r.worst_total.position.x(), r.worst_total.position.y()});
  for (const FlapStrains& f : r.flaps) {
    const std::string g = "/flaps/" + f.name;
    auto column = [&](auto getter) {
      std::vector<double> v;
      for (const SectionStrains& s : f.strains) v.push_back(getter(s));
      return v;
    };
    w.write(g + "/element", f.element, "1", "material element (materials.h5) of each beam segment");
    w.write(g + "/s", f.s, "m", "arc length of the segment middle");
    w.write(g + "/position", positions(f.position), "m", "reference position of the segment middle");
    w.write(g + "/mechanical_inner", column([](const SectionStrains& s) { return s.mechanical_inner; }), "1", "");
    w.write(g + "/mechanical_outer", column([](const SectionStrains& s) { return s.mechanical_outer; }), "1", "");
    w.write(g + "/thermal_inner", column([](const SectionStrains& s) { return s.thermal_inner; }), "1", "");
    w.write(g + "/thermal_outer", column([](const SectionStrains& s) { return s.thermal_outer; }), "1", "");
    w.write(g + "/total_inner", column([](const SectionStrains& s) { return s.total_inner; }), "1", "");
    w.write(g + "/total_outer", column([](const SectionStrains& s) { return s.total_outer; }), "1", "");
    w.write(g + "/allowable", f.allowable, "1", "allowable strain at the element temperature");
    w.write(g + "/margin_mechanical", f.margin_mechanical, "1", "allowable / max |mechanical| - 1");
    w.write(g + "/margin_thermal", f.margin_thermal, "1", "allowable / max |thermal| - 1");
    w.write(g + "/margin_total", f.margin_total, "1", "allowable / max |total| - 1");
  }
  std::vector<std::string> flap, surface;
  std::vector<std::int64_t> segment, element;
  std::vector<double> s, strain, margin;
  std::vector<Eigen::Vector2d> position;
  for (const Worst& x : r.worst_list) {
    flap.push_back(x.flap);
    surface.push_back(x.surface);
    segment.push_back(static_cast<std::int64_t>(x.segment));
    element.push_back(x.element);
    s.push_back(x.s);
    strain.push_back(x.strain);
    margin.push_back(x.margin);
    position.push_back(x.position);
  }
  w.write_strings("/worst/flap", flap, "flap of each of the lowest total margins, ascending");
  w.write_strings("/worst/surface", surface, "inner or outer");
  w.write("/worst/segment", segment, "1", "segment within the flap");
  w.write("/worst/element", element, "1", "material element");
  w.write("/worst/s", s, "m", "arc length");
  w.write("/worst/position", positions(position), "m", "");
  w.write("/worst/total_strain", strain, "1", "");
  w.write("/worst/margin_total", margin, "1", "");
  formats::write_provenance(w, provenance);
  w.commit();
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
  const std::filesystem::path tmp = file.string() + ".tmp";
  {
    std::ofstream out(tmp);
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
    if (!out) throw InternalError(tmp.string() + ": cannot write");
  }
  std::filesystem::rename(tmp, file);
}

}  // namespace tfmb::strain
