// The `thermal` file kind (formats/thermal.md): the temperature of the flap walls on the solid
// mesh and per beam element, written by tfmb-heat and read by tfmb-matmap. read_thermal checks the
// file against the kind's schema (what tfmb-check applies) and that temperatures are temperatures.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "tfmb/formats/files.hpp"

namespace tfmb::formats {

struct ThermalBeamFlap {
  std::string name;
  std::vector<double> mean_temperature;   // [K] area mean per beam element
  std::vector<double> delta_temperature;  // [K] outer minus inner surface
};

struct Thermal : ReadFrom {
  Header header;
  Mesh mesh;                          // the solid mesh
  std::vector<double> temperature;    // [K] per node
  h5::MatrixXdR heat_flux;            // (N,3) [W/m^2] q = -k grad T, or empty
  std::vector<ThermalBeamFlap> beam;  // by flap name
  bool converged = false;
  std::int64_t iterations = 0;
  std::string criterion;

  const ThermalBeamFlap* find_flap(const std::string& name) const { return find_named(beam, name); }
};

// Writes thermal.h5 atomically and its XDMF sidecar.
void write_thermal(const std::filesystem::path& file, const Thermal& thermal,
                   const Provenance& provenance);
// Reads and validates a thermal file (BadInput naming the file and the object on any problem).
Thermal read_thermal(const std::filesystem::path& file);

}  // namespace tfmb::formats
