#include "io.hpp"

#include <algorithm>
#include <sstream>

#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/formats/material_db.hpp"
#include "tfmb/formats/model.hpp"
#include "tfmb/formats/schema.hpp"
#include "tfmb/formats/thermal.hpp"

namespace tfmb::matmap {

MaterialDatabase read_material_db(const std::filesystem::path& file) {
  const formats::MaterialDatabase in = formats::read_material_db(file);
  MaterialDatabase db;
  db.default_titanium = in.default_titanium;
  for (const formats::DatabaseMaterial& entry : in.materials) {
    Material m;
    m.name = entry.name;
    m.description = entry.description;
    m.aliases = entry.aliases;
    m.reference_temperature = entry.reference_temperature;
    m.missing = entry.missing;
    for (const auto& [property, table] : entry.properties)
      m.properties[property] = {property, table.units, table.temperature, table.value,
                                table.exactness};
    db.materials.push_back(std::move(m));
  }
  return db;
}

Model read_model(const std::filesystem::path& file) {
  const formats::Model in = formats::read_model(file);
  Model model;
  model.header.geometry = in.geometry;
  model.header.depth = in.depth;
  for (const formats::Flap& f : in.flaps) {
    ModelFlap flap;
    static_cast<formats::Flap&>(flap) = f;
    const std::string g = "/flaps/" + f.name;
    const auto& curve = f.reference_curve;
    // Which side the outer wall is on: from the middle of the reference curve to the nearest
    // outer wall point, against the left normal there.
    const std::size_t j = (curve.size() - 1) / 2;
    const Eigen::Vector2d a = curve[j], b = curve[j + 1];
    const Eigen::Vector2d middle = 0.5 * (a + b);
    const Eigen::Vector2d normal(-(b - a).y(), (b - a).x());
    std::size_t nearest = 0;
    for (std::size_t i = 1; i < f.outer_wall.size(); ++i) {
      if ((f.outer_wall[i] - middle).norm() < (f.outer_wall[nearest] - middle).norm())
        nearest = i;
    }
    const double side = normal.dot(f.outer_wall[nearest] - middle);
    if (side == 0.0)
      in.fail(g + "/outer_wall", "lies on the reference curve: cannot tell the outer side");
    flap.outer_normal_sign = side > 0.0 ? 1 : -1;
    model.flaps.push_back(flap);
  }
  // The stage's outputs list flaps by name, as the file's groups are.
  std::sort(model.flaps.begin(), model.flaps.end(),
            [](const ModelFlap& a, const ModelFlap& b) { return a.name < b.name; });
  if (in.thermal.reference_temperature > 0.0)
    model.stress_free_temperature = in.thermal.reference_temperature;
  return model;
}

std::map<std::string, ThermalFlap> read_thermal(const std::filesystem::path& file) {
  std::map<std::string, ThermalFlap> out;
  for (const formats::ThermalBeamFlap& flap : formats::read_thermal(file).beam)
    out[flap.name] = {flap.mean_temperature, flap.delta_temperature};
  return out;
}

}  // namespace tfmb::matmap
