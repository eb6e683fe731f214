// In-memory description of a beam/multibody model: the solver's input.
//
// Units are SI throughout ([m], [N], [kg], [s], [rad]); nothing in the solver assumes a unit system,
// so the textbook benchmarks (E = 1e7, R = 100) run in their own consistent units.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace tfmb::beam {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// Cross-section properties in the section's material frame (axis 1 along the beam, 2 and 3 in the
/// section). Strain order (e11, 2 e12, 2 e13, k1, k2, k3); force order (N, V2, V3, T, M2, M3).
struct Section {
  Matrix6d stiffness = Matrix6d::Zero();  // [N] (force block), [N m] (coupling), [N m^2] (moment block)
  double mass_per_length = 0.0;           // [kg/m]
  Eigen::Matrix3d inertia_per_length = Eigen::Matrix3d::Zero();  // [kg m], about the section's centroid
};

/// A diagonal (doubly symmetric, isotropic) section: C = diag(EA, GA2, GA3, GJ, EI2, EI3) and the
/// mass matrix diag(m, m, m, I2 + I3, I2, I3) (polar inertia from the two bending inertias).
Section make_diagonal_section(double ea, double ga2, double ga3, double gj, double ei2, double ei3,
                              double mass_per_length = 0.0, double i2 = 0.0, double i3 = 0.0);

struct Node {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();       // reference position [m]
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();      // reference section frame (column 0: beam axis)
};

/// Quadratic 3-node element: nodes {end, middle, end}.
struct Element {
  std::array<int, 3> nodes{};
  int section = 0;
  /// Stress-free (initial) strains, e.g. thermal: (alpha dT, 0, 0, 0, alpha dT2/h2, alpha dT3/h3),
  /// same order as Section::stiffness.
  Vector6d initial_strain = Vector6d::Zero();
};

struct NodalLoad {
  int node = 0;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   // [N]
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();  // [N m]
  /// false: dead (fixed spatial direction); true: follower (given in the node's material frame,
  /// turning with it).
  bool follower = false;
};

struct DistributedLoad {
  int element = 0;
  Eigen::Vector3d force_per_length = Eigen::Vector3d::Zero();  // [N/m] per unit reference length
  /// true: the load is given in the deformed section frame and turns with it (pressure).
  bool follower = false;
};

enum class JointKind {
  clamp,      // node fixed in position and rotation (ground)
  rigid,      // two nodes rigidly connected
  revolute,   // hinge about `axis`; relative rotation phi is an extra unknown
  clearance,  // revolute with radial clearance: pin on node_b in a hole on node_a
  planar,     // keeps node_b in the x-y plane (z, rotations about x and y held)
  flexible,   // bushing: elastic energy of the relative motion of node_b (handle l) w.r.t. node_a
              // (k)
  // Lower pairs between node_a (or the ground) and node_b, coincident in the reference
  // configuration, about/along `axis` (3D models only):
  spherical,    // common point; rotation free
  cylindrical,  // rotation about and sliding along the axis
  prismatic,    // sliding along the axis only
  screw,        // rotation phi about the axis (extra unknown) with sliding screw_lead * phi
  planar_pair,  // node_b moves in the plane normal to the axis and turns about the axis only
  // Planar models only:
  pin_in_slot,  // node_b's pin slides along `axis` (in the x-y plane) and turns freely
};

struct FlexibleJointLaw;  // flexible_joint.hpp

/// Joint data. node_a = -1 means the ground (a fixed frame).
struct JointSpec {
  JointKind kind = JointKind::clamp;
  std::string name;
  int node_a = -1;
  int node_b = 0;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // hinge axis in the reference configuration
  // revolute options
  double spring_stiffness = 0.0;  // [N m/rad]
  double spring_rest_angle = 0.0; // [rad]
  double damping = 0.0;           // [N m s/rad]
  bool prescribed = false;        // actuator: phi(t) = prescribed_angle * load factor (or time fn)
  double prescribed_angle = 0.0;  // [rad]
  /// Optional actuator table (argument, angle [rad]); the argument is the load factor in statics
  /// and the time [s] in dynamics. Overrides prescribed_angle when not empty.
  std::vector<std::pair<double, double>> prescribed_table;
  // clearance options
  double hole_radius = 0.0;       // [m]
  double pin_radius = 0.0;        // [m]
  double contact_stiffness = 0.0; // [N/m] penalty
  double friction_coefficient = 0.0;
  double friction_regularisation_speed = 1e-3;  // [m/s]
  double screw_lead = 0.0;        // screw: sliding per radian of rotation [m/rad]
  // flexible options: stiffness, measures, joint frame (required for kind flexible)
  std::shared_ptr<const FlexibleJointLaw> flexible_law;
};

struct Model {
  std::vector<Node> nodes;
  std::vector<Section> sections;
  std::vector<Element> elements;
  std::vector<JointSpec> joints;
  std::vector<NodalLoad> nodal_loads;
  std::vector<DistributedLoad> distributed_loads;
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();  // [m/s^2], applied as dead load m g
  /// Planar model in the x-y plane: joints keep only their in-plane equations (x, y, rotation
  /// about z); out-of-plane motion is removed by `planar` joints on every node.
  bool planar = false;
};

/// Adds a planar joint on every node (for planar models).
void add_planar_constraints(Model& model);

/// Builds a straight or curved chain of `n_elements` quadratic elements along a curve given by
/// position(s) and tangent(s), s in [0, 1]; the section frame has e1 = tangent and e3 = `normal3`
/// projected orthogonal to the tangent. Returns the node ids (2 n + 1) appended to `model`.
template <typename Position, typename Tangent>
std::vector<int> add_beam(Model& model, int n_elements, int section, Position position, Tangent tangent,
                          const Eigen::Vector3d& normal3 = Eigen::Vector3d::UnitZ());

}  // namespace tfmb::beam

#include "tfmb-beam/model_impl.hpp"
