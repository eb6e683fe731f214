#include "mesh_dual.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <type_traits>
#include <unordered_map>

namespace tfmb::flow {

namespace {

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}

// Normal of the straight segment p->q, length |q - p|, turned to agree with `towards`.
Vec2 segment_normal(Vec2 p, Vec2 q, Vec2 towards) {
  Vec2 n{q.y - p.y, -(q.x - p.x)};
  if (dot(n, towards) < 0.0) n = -1.0 * n;
  return n;
}

// Signed area and signed first moment about the axis (integral of y dA) of a polygon.
void polygon_area_moment(const Vec2* v, int nv, double& area, double& moment_y) {
  area = 0.0;
  moment_y = 0.0;
  for (int k = 0; k < nv; ++k) {
    const Vec2 a = v[k];
    const Vec2 b = v[(k + 1) % nv];
    const double cross = a.x * b.y - b.x * a.y;
    area += 0.5 * cross;
    moment_y += cross * (a.y + b.y) / 6.0;
  }
}

// Edges in the order of their nodes (first, then second): an edge loop then walks the node
// arrays forward instead of in the cells' order, and a static split of it between threads gives
// each thread the edges of a range of nodes.
void sort_edges_by_nodes(DualMesh& d) {
  std::vector<int> order(d.edges.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return d.edges[a] < d.edges[b]; });
  auto permuted = [&](const auto& v) {
    std::remove_cvref_t<decltype(v)> out(v.size());
    for (std::size_t k = 0; k < order.size(); ++k)
      out[k] = v[order[k]];
    return out;
  };
  d.edges = permuted(d.edges);
  d.edge_normal = permuted(d.edge_normal);
  d.edge_normal_planar = permuted(d.edge_normal_planar);
}

}  // namespace

DualMesh build_dual(const Mesh& mesh, Geometry geometry) {
  DualMesh d;
  d.geometry = geometry;
  d.num_nodes = mesh.num_points();
  d.coords = mesh.points;
  d.volume.assign(d.num_nodes, 0.0);
  d.area.assign(d.num_nodes, 0.0);
  const bool axi = geometry == Geometry::axisymmetric;

  std::unordered_map<std::uint64_t, int> edge_id;
  edge_id.reserve(static_cast<std::size_t>(mesh.num_cells()) * 3);
  // For boundary edges: the centroid of the (single) cell owning them, to orient outwards.
  std::vector<Vec2> edge_cell_centroid;

  auto add_cell = [&](const int* ids, int nv) {
    Vec2 c{};
    for (int k = 0; k < nv; ++k) c = c + mesh.points[ids[k]];
    c = (1.0 / nv) * c;  // median dual uses the vertex average (Blazek 2015, fig. 5.8)
    for (int k = 0; k < nv; ++k) {
      const int a = ids[k];
      const int b = ids[(k + 1) % nv];
      const int prev = ids[(k + nv - 1) % nv];
      const Vec2 pa = mesh.points[a];
      const Vec2 pb = mesh.points[b];
      const Vec2 m = 0.5 * (pa + pb);
      auto [it, inserted] = edge_id.try_emplace(edge_key(a, b), d.num_edges());
      if (inserted) {
        d.edges.push_back({std::min(a, b), std::max(a, b)});
        d.edge_normal.push_back({});
        d.edge_normal_planar.push_back({});
        edge_cell_centroid.push_back(c);
      }
      const int e = it->second;
      const Vec2 from_first_to_second = mesh.points[d.edges[e][1]] - mesh.points[d.edges[e][0]];
      const Vec2 n = segment_normal(m, c, from_first_to_second);
      d.edge_normal_planar[e] = d.edge_normal_planar[e] + n;
      // integral of r n ds over a straight segment: r varies linearly, so the midpoint rule is exact
      d.edge_normal[e] = d.edge_normal[e] + (axi ? 0.5 * (m.y + c.y) : 1.0) * n;

      // Sub-region of node a's dual cell inside this cell: a, mid(a,b), centroid, mid(prev,a).
      const Vec2 poly[4] = {pa, m, c, 0.5 * (pa + mesh.points[prev])};
      double area = 0.0;
      double moment = 0.0;
      polygon_area_moment(poly, 4, area, moment);
      if (area < 0.0) {
        area = -area;
        moment = -moment;
      }
      d.area[a] += area;
      d.volume[a] += axi ? moment : area;
    }
  };
  for (const auto& t : mesh.triangles) add_cell(t.data(), 3);
  for (const auto& q : mesh.quads) add_cell(q.data(), 4);

  for (int b = 0; b < static_cast<int>(mesh.boundaries.size()); ++b) {
    const auto& curve = mesh.boundaries[b];
    for (int k = 0; k < static_cast<int>(curve.edges.size()); ++k) {
      const int a = curve.edges[k][0];
      const int c = curve.edges[k][1];
      const auto it = edge_id.find(edge_key(a, c));
      if (it == edge_id.end()) {
        throw std::invalid_argument("mesh: boundary '" + curve.name + "' has an edge that is no cell edge");
      }
      const Vec2 pa = mesh.points[a];
      const Vec2 pc = mesh.points[c];
      const Vec2 m = 0.5 * (pa + pc);
      const Vec2 outward = m - edge_cell_centroid[it->second];
      const Vec2 na = segment_normal(pa, m, outward);
      const Vec2 nc = segment_normal(m, pc, outward);
      const double wa = axi ? 0.5 * (pa.y + m.y) : 1.0;
      const double wc = axi ? 0.5 * (m.y + pc.y) : 1.0;
      d.boundary_faces.push_back({a, b, k, wa * na, 0.5 * (pa + m)});
      d.boundary_faces.push_back({c, b, k, wc * nc, 0.5 * (m + pc)});
    }
  }

  sort_edges_by_nodes(d);

  // Node -> edge incidence (CSR), neighbours in edge order; used for deterministic gathers.
  auto& ne = d.node_edges;
  ne.offsets.assign(d.num_nodes + 1, 0);
  for (const auto& e : d.edges) {
    ++ne.offsets[e[0] + 1];
    ++ne.offsets[e[1] + 1];
  }
  for (int i = 0; i < d.num_nodes; ++i) ne.offsets[i + 1] += ne.offsets[i];
  const int total = ne.offsets[d.num_nodes];
  ne.edge.resize(total);
  ne.neighbour.resize(total);
  ne.sign.resize(total);
  std::vector<int> fill(ne.offsets.begin(), ne.offsets.end() - 1);
  for (int e = 0; e < d.num_edges(); ++e) {
    const int i = d.edges[e][0];
    const int j = d.edges[e][1];
    ne.edge[fill[i]] = e;
    ne.neighbour[fill[i]] = j;
    ne.sign[fill[i]++] = 1.0;
    ne.edge[fill[j]] = e;
    ne.neighbour[fill[j]] = i;
    ne.sign[fill[j]++] = -1.0;
  }
  return d;
}

std::vector<Vec2> dual_closure(const DualMesh& dual) {
  std::vector<Vec2> sum(dual.num_nodes);
  for (int e = 0; e < dual.num_edges(); ++e) {
    sum[dual.edges[e][0]] = sum[dual.edges[e][0]] + dual.edge_normal[e];
    sum[dual.edges[e][1]] = sum[dual.edges[e][1]] - dual.edge_normal[e];
  }
  for (const auto& f : dual.boundary_faces) sum[f.node] = sum[f.node] + f.normal;
  return sum;
}

}  // namespace tfmb::flow
