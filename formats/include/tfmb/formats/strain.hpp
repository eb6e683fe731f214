// The `strain` file kind (formats/strain.md): fibre strains and margins of every flap, written by
// tfmb-strain and read by tfmb-plot (Python, formats/python/tfmbfiles.py) and by tests.
// read_strain checks the file against the kind's schema (what tfmb-check applies) and that every
// flap's columns have one value per segment.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "tfmb/formats/files.hpp"

namespace tfmb::formats {

// One flap: a row per beam segment, in order from the flap's start.
struct StrainFlap {
  std::string name;
  std::vector<std::int64_t> element;      // material element (materials.h5) of each segment
  std::vector<double> s;                  // [m] arc length of the segment middle
  std::vector<Eigen::Vector2d> position;  // [m] reference position of the segment middle
  std::vector<double> mechanical_inner, mechanical_outer;  // [1] fibre strains
  std::vector<double> thermal_inner, thermal_outer;
  std::vector<double> total_inner, total_outer;
  std::vector<double> allowable;  // [1] at the element temperature
  std::vector<double> margin_mechanical, margin_thermal, margin_total;  // allowable / max|.| - 1
};

// One of the lowest total margins (the /worst table, ascending).
struct StrainWorst {
  std::string flap;
  std::string surface;  // inner | outer
  std::int64_t segment = 0;
  std::int64_t element = 0;
  double s = 0.0;                                      // [m]
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // [m]
  double total_strain = 0.0;
  double margin_total = 0.0;
};

struct Strain : ReadFrom {
  Header header;
  std::string mechanical_basis;  // mechanical | force
  double worst_margin_total = 0.0, worst_margin_mechanical = 0.0, worst_margin_thermal = 0.0;
  std::string worst_flap, worst_surface;
  std::int64_t worst_segment = 0;
  Eigen::Vector2d worst_position = Eigen::Vector2d::Zero();
  std::vector<StrainFlap> flaps;  // by name
  std::vector<StrainWorst> worst;
};

// Writes strain.h5 atomically.
void write_strain(const std::filesystem::path& file, const Strain& strain,
                  const Provenance& provenance);
// Reads and validates a strain file (BadInput naming the file and the object on any problem).
Strain read_strain(const std::filesystem::path& file);

}  // namespace tfmb::formats
