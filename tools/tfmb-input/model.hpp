// The analysis model tfmb-input builds: the model file kind's own types (formats/model.hpp), used
// under tfmb-input's namespace. write_model/read_model are formats'.
#pragma once

#include "tfmb/common/geometry.hpp"
#include "tfmb/formats/model.hpp"

namespace tfmb::input {

using formats::AnalysisSettings;
using formats::Domain;
using formats::DomainBoundary;
using formats::DomainSettings;
using formats::Flap;
using formats::FlowConditions;
using formats::Joint;
using formats::Matrix6;
using formats::MeshControls;
using formats::Model;
using formats::Section;
using formats::Support;
using formats::ThermalSettings;
using geometry::Point;
using geometry::Polyline;

}  // namespace tfmb::input
