// From case settings + geometry curves to the model: flap reference lines and their beam
// discretisation, sections, walls, joints, supports and the flow domain, with the checks that
// catch drawing mistakes (gaps, overlaps, self-intersections, joints away from flap ends).
#pragma once

#include <vector>

#include "case_file.hpp"
#include "geometry_io.hpp"
#include "model.hpp"
#include "tfmb/common/log.hpp"

namespace tfmb::input {

// Rectangular section of thickness t (in-plane) and width b (depth), Timoshenko shear factor
// 5/6; see section.cpp for the formulas and their sources.
Section rectangle_section(double thickness, double width, double youngs_modulus,
                          double poisson_ratio, double density);

// Throws BadInput naming the curves/flaps/joint and the location for every failed check.
Model build_model(const CaseSpec& spec, const std::vector<Curve>& curves, const Logger& log);

// The flow domain loop of a model whose flaps are built (also used by tests).
Domain build_domain(const Model& model, const std::vector<Curve>& curves);

struct Options {
  std::filesystem::path case_file;
  std::filesystem::path output;
  std::vector<std::string> overrides;
  std::filesystem::path curves_csv;  // optional: write the curves read from the geometry
  std::string command_line;
};

// The whole tfmb-input run: read case and geometry, build, write model.h5.
void run(const Options& options, const Logger& log);

}  // namespace tfmb::input
