// case.toml: the one file a user writes (formats/case-toml.md documents every key). Reading is
// strict: unknown keys, wrong types and values out of range are BadInput errors that name the
// file, the line and the key.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "model.hpp"

namespace tfmb::input {

struct GeometrySettings {
  std::filesystem::path file;      // resolved against the directory of case.toml
  double scale = 1.0;              // coordinates * scale = metres
  double tolerance = 1e-6;         // [m] largest accepted gap/overlap where curves meet
  int curve_samples = 64;          // points per CAD curve (STEP/IGES/geo)
};

struct FlapSpec {
  Flap flap;                       // settings only; geometry filled by build_model
  std::string reference = "mid";   // which surface the curves describe: mid | inner | outer
  int line = 0;                    // line in case.toml, for messages
};

struct JointSpec {
  Joint joint;                     // flap_a/flap_b from `flaps`, ends found by build_model
  std::optional<Point> point;      // [m] if given, must lie at an end of both flaps
  int line = 0;
};

struct SupportSpec {
  Support support;
  int line = 0;
};

struct CaseSpec {
  std::filesystem::path file;
  GeometrySettings geometry;       // geometry.file empty: structure/flow cases without curves
  std::vector<FlapSpec> flaps;
  std::vector<JointSpec> joints;
  std::vector<SupportSpec> supports;
  Model settings;                  // title, depth, domain settings, flow, thermal, mesh, analysis
  std::string resolved_toml;       // the case after --set overrides, for /provenance
};

// Reads case.toml and applies "key=value" overrides (dotted keys; an element of an array of
// tables is addressed by its name, e.g. "flap.upper_div.thickness=0.004").
CaseSpec read_case(const std::filesystem::path& file, const std::vector<std::string>& overrides);

// Viscous length nu/u_tau [m] from a flat-plate skin-friction estimate at the nozzle throat (or
// free stream) conditions: a first cell of height h has y+ = h / viscous_length. 0 where the
// conditions give no estimate (no flow, T0 = 0).
double viscous_length(const FlowConditions& flow);

}  // namespace tfmb::input
