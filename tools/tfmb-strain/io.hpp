// Every file tfmb-strain reads or writes goes through here (formats/structure.md,
// materials.md, strain.md).
#pragma once

#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "fibre_strain.hpp"
#include "tfmb/formats/files.hpp"

namespace tfmb::strain {

struct StructureFlap {
  std::vector<std::int64_t> segments;           // rows of the structure's cell fields
  std::vector<Eigen::Vector2d> segment_middle;  // reference position of each segment's middle [m]
  std::vector<double> segment_arc_length;       // at the middle, from the flap start [m]
};
struct Structure {
  formats::Header header;
  bool converged = true;
  std::vector<std::array<double, 6>> sectional_strain;  // per segment
  std::vector<std::array<double, 6>> sectional_force;
  std::map<std::string, StructureFlap> flaps;
};
Structure read_structure(const std::filesystem::path& file);

struct MaterialsFlap {
  double thickness = 0.0;
  int outer_normal_sign = 1;
  std::string material;
  std::vector<double> temperature, allowable_strain, thermal_strain_inner, thermal_strain_outer, thermal_strain,
      thermal_curvature;
  std::vector<double> axial_stiffness, bending_stiffness;  // EA, EI3 per element
  std::vector<std::int64_t> clamped;
};
std::map<std::string, MaterialsFlap> read_materials(const std::filesystem::path& file);

struct FlapStrains {
  std::string name;
  std::vector<std::int64_t> element;  // material element of each segment
  std::vector<double> s;              // arc length of the segment middle [m]
  std::vector<Eigen::Vector2d> position;
  std::vector<SectionStrains> strains;
  std::vector<double> allowable, margin_mechanical, margin_thermal, margin_total;
};

struct Worst {
  std::string flap;
  std::size_t segment = 0;
  std::int64_t element = 0;
  std::string surface;  // inner or outer
  double s = 0.0;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  double strain = 0.0;  // of the category
  double allowable = 0.0;
  double margin = 0.0;
};

struct StrainResult {
  MechanicalBasis basis = MechanicalBasis::mechanical;
  std::vector<FlapStrains> flaps;
  Worst worst_mechanical, worst_thermal, worst_total;
  std::vector<Worst> worst_list;  // lowest total margins, ascending
};

void write_strain(const std::filesystem::path& file, const formats::Header& header, const StrainResult& result,
                  const formats::Provenance& provenance);
void write_summary_json(const std::filesystem::path& file, const StrainResult& result);

}  // namespace tfmb::strain
