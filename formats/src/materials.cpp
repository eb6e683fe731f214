// The materials kind's one reader and writer: formats/materials.md (schema in
// schema_materials.cpp).
#include "tfmb/formats/materials.hpp"

#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/formats/schema.hpp"

namespace tfmb::formats {
namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;

void write_stack(h5::Writer& w, const std::string& path, const std::vector<Matrix6>& m,
                 const std::string& units, const std::string& description) {
  std::vector<double> values;
  for (const Matrix6& a : m)
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c)
        values.push_back(a(r, c));
  w.write_array(path, values, {m.size(), 6, 6}, units, description);
}

std::vector<Matrix6> read_stack(const h5::Reader& r, const std::string& path,
                                std::size_t elements) {
  std::vector<std::size_t> shape;
  const std::vector<double> values = r.read_f64(path, &shape);
  if (shape != std::vector<std::size_t>{elements, 6, 6})
    r.fail(path, "shape must be (" + std::to_string(elements) + ",6,6), one matrix per element");
  std::vector<Matrix6> out(elements);
  for (std::size_t e = 0; e < elements; ++e)
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        out[e](i, j) = values[36 * e + 6 * static_cast<std::size_t>(i) + j];
  return out;
}

MaterialsFlap read_flap(const h5::Reader& r, const std::string& name) {
  const std::string g = "/flaps/" + name;
  MaterialsFlap f;
  f.name = name;
  f.material = r.attr_string(g, "material");
  f.material_given = r.attr_string(g, "material_given");
  f.thickness = r.attr_f64(g, "thickness");
  f.width = r.attr_f64(g, "width");
  f.reference_temperature = r.attr_f64(g, "reference_temperature");
  f.stress_free_temperature = r.attr_f64(g, "stress_free_temperature");
  f.outer_normal_sign = static_cast<int>(r.attr_i64(g, "outer_normal_sign"));
  f.shear_modulus_basis = r.attr_string(g, "shear_modulus_basis");
  f.allowable_strain_basis = r.attr_string(g, "allowable_strain_basis");
  if (!(f.thickness > 0.0))
    r.fail(g, "thickness must be positive");
  if (!(f.width > 0.0))
    r.fail(g, "width must be positive");
  if (f.outer_normal_sign != 1 && f.outer_normal_sign != -1)
    r.fail(g, "outer_normal_sign must be +1 or -1");
  MaterialElements& e = f.elements;
  e.temperature = r.read_vector(g + "/temperature");
  const std::size_t ne = e.temperature.size();
  if (ne == 0)
    r.fail(g + "/temperature", "no elements");
  e.delta_temperature = r.read_vector(g + "/delta_temperature", ne);
  e.youngs_modulus = r.read_vector(g + "/youngs_modulus", ne);
  e.shear_modulus = r.read_vector(g + "/shear_modulus", ne);
  e.poisson_ratio = r.read_vector(g + "/poisson_ratio", ne);
  e.thermal_expansion = r.read_vector(g + "/thermal_expansion", ne);
  e.density = r.read_vector(g + "/density", ne);
  f.has_strength = r.exists(g + "/yield_strength");
  if (f.has_strength) {
    e.yield_strength = r.read_vector(g + "/yield_strength", ne);
    e.ultimate_strength = r.read_vector(g + "/ultimate_strength", ne);
  }
  e.allowable_strain = r.read_vector(g + "/allowable_strain", ne);
  e.thermal_strain = r.read_vector(g + "/thermal_strain", ne);
  e.thermal_strain_inner = r.read_vector(g + "/thermal_strain_inner", ne);
  e.thermal_strain_outer = r.read_vector(g + "/thermal_strain_outer", ne);
  e.thermal_curvature = r.read_vector(g + "/thermal_curvature", ne);
  e.section_stiffness = read_stack(r, g + "/section_stiffness", ne);
  e.section_mass = read_stack(r, g + "/section_mass", ne);
  e.clamped = r.read_index_vector(g + "/clamped", ne, 0, 2);
  for (std::size_t k = 0; k < ne; ++k) {
    const std::string element = "element " + std::to_string(k) + ": ";
    if (!(e.temperature[k] > 0.0))
      r.fail(g + "/temperature", element + "not a temperature");
    if (!(e.allowable_strain[k] > 0.0))
      r.fail(g + "/allowable_strain", element + "not positive");
    for (int i = 0; i < 6; ++i)
      if (!(e.section_stiffness[k](i, i) > 0.0))
        r.fail(g + "/section_stiffness",
               element + "diagonal entry " + std::to_string(i) + " must be > 0");
    if (!(e.section_mass[k](0, 0) >= 0.0))
      r.fail(g + "/section_mass", element + "mass per length must be >= 0");
  }
  return f;
}

}  // namespace

void write_materials(const std::filesystem::path& file, const Header& header,
                     const std::vector<MaterialsFlap>& flaps, const Provenance& provenance) {
  h5::Writer w(file);
  write_header(w, "materials", header);
  for (const MaterialsFlap& f : flaps) {
    const std::string g = "/flaps/" + f.name;
    const MaterialElements& e = f.elements;
    w.write(g + "/temperature", e.temperature, "K", "mean temperature of each beam element");
    w.write(g + "/delta_temperature", e.delta_temperature, "K",
            "outer minus inner surface temperature");
    w.write(g + "/youngs_modulus", e.youngs_modulus, "Pa", "at the element temperature");
    w.write(g + "/shear_modulus", e.shear_modulus, "Pa", f.shear_modulus_basis);
    w.write(g + "/poisson_ratio", e.poisson_ratio, "1", "");
    w.write(g + "/thermal_expansion", e.thermal_expansion, "1/K",
            "mean coefficient from reference_temperature");
    w.write(g + "/density", e.density, "kg/m^3", "");
    if (f.has_strength) {
      w.write(g + "/yield_strength", e.yield_strength, "Pa", "");
      w.write(g + "/ultimate_strength", e.ultimate_strength, "Pa", "");
    }
    w.write(g + "/allowable_strain", e.allowable_strain, "1", f.allowable_strain_basis);
    w.write(g + "/thermal_strain", e.thermal_strain, "1",
            "section mean of the free thermal strain through the thickness");
    w.write(g + "/thermal_strain_inner", e.thermal_strain_inner, "1",
            "at the inner surface (T - dT/2)");
    w.write(g + "/thermal_strain_outer", e.thermal_strain_outer, "1",
            "at the outer surface (T + dT/2)");
    w.write(g + "/thermal_curvature", e.thermal_curvature, "1/m",
            "(thermal_strain_outer - thermal_strain_inner) / thickness, positive towards the outer "
            "surface");
    write_stack(w, g + "/section_stiffness", e.section_stiffness, "N, N m^2",
                "rectangle thickness x width");
    write_stack(w, g + "/section_mass", e.section_mass, "kg/m, kg m",
                "rectangle thickness x width");
    w.write(g + "/clamped", e.clamped, "1",
            "1 if a temperature was outside a table and the end value was used");
    w.set_attr(g, "material", f.material);
    w.set_attr(g, "material_given", f.material_given);
    w.set_attr(g, "thickness", f.thickness);
    w.set_attr(g, "width", f.width);
    w.set_attr(g, "reference_temperature", f.reference_temperature);
    w.set_attr(g, "stress_free_temperature", f.stress_free_temperature);
    w.set_attr(g, "outer_normal_sign", static_cast<std::int64_t>(f.outer_normal_sign));
    w.set_attr(g, "shear_modulus_basis", f.shear_modulus_basis);
    w.set_attr(g, "allowable_strain_basis", f.allowable_strain_basis);
    std::int64_t clamped = 0;
    for (auto c : e.clamped)
      clamped += c;
    w.set_attr(g, "clamped_elements", clamped);
  }
  write_provenance(w, provenance);
  w.commit();
}

Materials read_materials(const std::filesystem::path& file) {
  const h5::Reader r = open_checked(file, "materials");
  Materials out;
  out.source = file;
  out.header = read_header(r);
  for (const std::string& name : r.children("/flaps"))
    out.flaps.push_back(read_flap(r, name));
  return out;
}

}  // namespace tfmb::formats
