#include <stdexcept>
#include <string>

#include "joint_common.hpp"

namespace tfmb::beam {

std::string Joint::equation_name(int i) const { return "equation " + std::to_string(i); }

std::unique_ptr<Joint> make_joint(const Model& model, const JointSpec& spec) {
  const int n = static_cast<int>(model.nodes.size());
  auto check_node = [&](int id, bool ground_ok, const char* which) {
    if ((ground_ok && id == -1) || (id >= 0 && id < n)) return;
    throw std::invalid_argument("joint '" + spec.name + "': " + which + " = " + std::to_string(id) +
                                " is not a node id (0.." + std::to_string(n - 1) + (ground_ok ? ", or -1 for ground)" : ")"));
  };
  check_node(spec.node_b, false, "node_b");
  switch (spec.kind) {
    case JointKind::clamp:
      return detail::make_clamp(model, spec);
    case JointKind::rigid:
      check_node(spec.node_a, false, "node_a");
      return detail::make_rigid(model, spec);
    case JointKind::revolute:
      check_node(spec.node_a, true, "node_a");
      return detail::make_revolute(model, spec);
    case JointKind::planar:
      return detail::make_planar(model, spec);
    case JointKind::flexible:
      check_node(spec.node_a, true, "node_a");
      return detail::make_flexible(model, spec);
    case JointKind::spherical:
    case JointKind::cylindrical:
    case JointKind::prismatic:
    case JointKind::screw:
    case JointKind::planar_pair:
    case JointKind::pin_in_slot:
      check_node(spec.node_a, true, "node_a");
      return detail::make_lower_pair(model, spec);
    case JointKind::clearance:
      check_node(spec.node_a, true, "node_a");
      return detail::make_clearance(model, spec);
  }
  throw std::invalid_argument("joint '" + spec.name + "': unknown kind");
}

}  // namespace tfmb::beam
