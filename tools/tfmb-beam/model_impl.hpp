#pragma once
// Template definitions for model.hpp.

namespace tfmb::beam {

template <typename Position, typename Tangent>
std::vector<int> add_beam(Model& model, int n_elements, int section, Position position, Tangent tangent,
                          const Eigen::Vector3d& normal3) {
  std::vector<int> ids;
  const int n_nodes = 2 * n_elements + 1;
  for (int i = 0; i < n_nodes; ++i) {
    const double s = static_cast<double>(i) / (n_nodes - 1);
    Node node;
    node.position = position(s);
    const Eigen::Vector3d e1 = tangent(s).normalized();
    Eigen::Vector3d e3 = normal3 - normal3.dot(e1) * e1;
    e3.normalize();
    node.frame.col(0) = e1;
    node.frame.col(1) = e3.cross(e1);
    node.frame.col(2) = e3;
    ids.push_back(static_cast<int>(model.nodes.size()));
    model.nodes.push_back(node);
  }
  for (int e = 0; e < n_elements; ++e) {
    Element el;
    el.nodes = {ids[2 * e], ids[2 * e + 1], ids[2 * e + 2]};
    el.section = section;
    model.elements.push_back(el);
  }
  return ids;
}

}  // namespace tfmb::beam
