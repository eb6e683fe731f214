// The strain kind's one reader and writer: formats/strain.md (schema in schema_strain.cpp).
#include "tfmb/formats/strain.hpp"

#include "tfmb/common/h5.hpp"
#include "tfmb/formats/schema.hpp"

namespace tfmb::formats {
namespace {

h5::MatrixXdR rows_of(const std::vector<Eigen::Vector2d>& p) {
  h5::MatrixXdR m(static_cast<Eigen::Index>(p.size()), 2);
  for (std::size_t i = 0; i < p.size(); ++i)
    m.row(static_cast<Eigen::Index>(i)) = p[i].transpose();
  return m;
}

std::vector<Eigen::Vector2d> points_of(const h5::MatrixXdR& m) {
  std::vector<Eigen::Vector2d> p(static_cast<std::size_t>(m.rows()));
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    p[static_cast<std::size_t>(i)] = m.row(i).transpose();
  return p;
}

// The per-segment columns of a flap, by dataset name (one list for the writer and the reader).
template <class Flap, class Visit>
void for_each_column(Flap& f, Visit visit) {
  visit("mechanical_inner", f.mechanical_inner, "");
  visit("mechanical_outer", f.mechanical_outer, "");
  visit("thermal_inner", f.thermal_inner, "");
  visit("thermal_outer", f.thermal_outer, "");
  visit("total_inner", f.total_inner, "");
  visit("total_outer", f.total_outer, "");
  visit("allowable", f.allowable, "allowable strain at the element temperature");
  visit("margin_mechanical", f.margin_mechanical, "allowable / max |mechanical| - 1");
  visit("margin_thermal", f.margin_thermal, "allowable / max |thermal| - 1");
  visit("margin_total", f.margin_total, "allowable / max |total| - 1");
}

}  // namespace

void write_strain(const std::filesystem::path& file, const Strain& strain,
                  const Provenance& provenance) {
  h5::Writer w(file);
  write_header(w, "strain", strain.header);
  w.set_attr("/", "mechanical_basis", strain.mechanical_basis);
  w.set_attr("/", "worst_margin_total", strain.worst_margin_total);
  w.set_attr("/", "worst_margin_mechanical", strain.worst_margin_mechanical);
  w.set_attr("/", "worst_margin_thermal", strain.worst_margin_thermal);
  w.set_attr("/", "worst_flap", strain.worst_flap);
  w.set_attr("/", "worst_segment", strain.worst_segment);
  w.set_attr("/", "worst_surface", strain.worst_surface);
  w.set_attr("/", "worst_position",
             std::vector<double>{strain.worst_position.x(), strain.worst_position.y()});
  for (const StrainFlap& f : strain.flaps) {
    const std::string g = "/flaps/" + f.name;
    w.write(g + "/element", f.element, "1", "material element (materials.h5) of each beam segment");
    w.write(g + "/s", f.s, "m", "arc length of the segment middle");
    w.write(g + "/position", rows_of(f.position), "m", "reference position of the segment middle");
    for_each_column(f, [&](const char* name, const std::vector<double>& column, const char* what) {
      w.write(g + "/" + name, column, "1", what);
    });
  }
  std::vector<std::string> flap, surface;
  std::vector<std::int64_t> segment, element;
  std::vector<double> s, total_strain, margin;
  std::vector<Eigen::Vector2d> position;
  for (const StrainWorst& x : strain.worst) {
    flap.push_back(x.flap);
    surface.push_back(x.surface);
    segment.push_back(x.segment);
    element.push_back(x.element);
    s.push_back(x.s);
    total_strain.push_back(x.total_strain);
    margin.push_back(x.margin_total);
    position.push_back(x.position);
  }
  w.write_strings("/worst/flap", flap, "flap of each of the lowest total margins, ascending");
  w.write_strings("/worst/surface", surface, "inner or outer");
  w.write("/worst/segment", segment, "1", "segment within the flap");
  w.write("/worst/element", element, "1", "material element");
  w.write("/worst/s", s, "m", "arc length");
  w.write("/worst/position", rows_of(position), "m", "");
  w.write("/worst/total_strain", total_strain, "1", "");
  w.write("/worst/margin_total", margin, "1", "");
  write_provenance(w, provenance);
  w.commit();
  write_xdmf_sidecar(file);
}

Strain read_strain(const std::filesystem::path& file) {
  // The schema has checked presence, dtypes, finite values and that each flap's columns (and the
  // /worst columns) share one length.
  const h5::Reader r = open_checked(file, "strain");
  Strain out;
  out.source = file;
  out.header = read_header(r);
  out.mechanical_basis = r.attr_string("/", "mechanical_basis");
  out.worst_margin_total = r.attr_f64("/", "worst_margin_total");
  out.worst_margin_mechanical = r.attr_f64("/", "worst_margin_mechanical");
  out.worst_margin_thermal = r.attr_f64("/", "worst_margin_thermal");
  out.worst_flap = r.attr_string("/", "worst_flap");
  out.worst_segment = r.attr_i64("/", "worst_segment");
  out.worst_surface = r.attr_string("/", "worst_surface");
  const std::vector<double> where = r.attr_f64_vector("/", "worst_position");
  if (where.size() != 2)
    r.fail("/", "worst_position has " + std::to_string(where.size()) + " values, expected 2");
  out.worst_position = {where[0], where[1]};
  for (const std::string& name : r.children("/flaps")) {
    const std::string g = "/flaps/" + name;
    StrainFlap f;
    f.name = name;
    f.element = r.read_i64(g + "/element");
    f.s = r.read_vector(g + "/s");
    f.position = points_of(r.read_matrix(g + "/position", f.s.size(), 2));
    for_each_column(f, [&](const char* column, std::vector<double>& values, const char*) {
      values = r.read_vector(g + "/" + column, f.s.size());
    });
    out.flaps.push_back(std::move(f));
  }
  if (out.flaps.empty())
    r.fail("/flaps", "no flaps");
  if (!find_named(out.flaps, out.worst_flap))
    r.fail("/", "worst_flap '" + out.worst_flap + "' is not a flap of /flaps");
  const std::vector<std::string> flap = r.read_strings("/worst/flap");
  const std::size_t n = flap.size();
  const std::vector<std::string> surface = r.read_strings("/worst/surface");
  const std::vector<std::int64_t> segment = r.read_i64("/worst/segment");
  const std::vector<std::int64_t> element = r.read_i64("/worst/element");
  const std::vector<double> s = r.read_vector("/worst/s", n);
  const std::vector<Eigen::Vector2d> position = points_of(r.read_matrix("/worst/position", n, 2));
  const std::vector<double> total_strain = r.read_vector("/worst/total_strain", n);
  const std::vector<double> margin = r.read_vector("/worst/margin_total", n);
  for (std::size_t i = 0; i < n; ++i) {
    StrainWorst x;
    x.flap = flap[i];
    x.surface = surface[i];
    x.segment = segment[i];
    x.element = element[i];
    x.s = s[i];
    x.position = position[i];
    x.total_strain = total_strain[i];
    x.margin_total = margin[i];
    out.worst.push_back(std::move(x));
  }
  return out;
}

}  // namespace tfmb::formats
