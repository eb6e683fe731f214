// Structured quad meshes of the simple validation domains: the quasi-1D channel (NPARC CDV
// nozzle: wall above, symmetry line below; axisymmetric models: the axis of revolution below,
// e.g. the Back-Massier-Gier cone) and the TMR flat plate (symmetry ahead of the plate,
// wall, outflow, far field, inflow), clustered to the walls by geometric stretching.
#include <algorithm>
#include <cmath>

#include "mesh_tools.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/polyline.hpp"

namespace tfmb::mesh {
namespace {

// n+1 coordinates from 0 to 1 whose first spacing is `first` (geometric progression; uniform if
// first >= 1/n). The ratio solves first (r^n - 1)/(r - 1) = 1 by bisection.
std::vector<double> geometric(int n, double first) {
  std::vector<double> t(static_cast<std::size_t>(n) + 1);
  if (first <= 0.0 || first * n >= 1.0) {
    for (int i = 0; i <= n; ++i) t[static_cast<std::size_t>(i)] = static_cast<double>(i) / n;
    return t;
  }
  double lo = 1.0 + 1e-12, hi = 2.0;
  auto total = [&](double r) { return first * (std::pow(r, n) - 1.0) / (r - 1.0); };
  while (total(hi) < 1.0) hi *= 2.0;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (total(mid) < 1.0 ? lo : hi) = mid;
  }
  const double r = 0.5 * (lo + hi);
  double x = 0.0, h = first;
  t[0] = 0.0;
  for (int i = 1; i <= n; ++i) {
    x += h;
    h *= r;
    t[static_cast<std::size_t>(i)] = x;
  }
  for (auto& v : t) v /= t.back();
  return t;
}

int cells(int given, int fallback, double scale) {
  const int n = given > 0 ? given : fallback;
  return std::max(2, static_cast<int>(std::lround(n / scale)));
}

formats::Boundary boundary(std::string kind, const std::vector<std::int64_t>& nodes) {
  formats::Boundary b;
  b.kind = std::move(kind);
  b.edges.resize(static_cast<Eigen::Index>(nodes.size() - 1), 2);
  for (std::size_t i = 0; i + 1 < nodes.size(); ++i) {
    b.edges(static_cast<Eigen::Index>(i), 0) = nodes[i];
    b.edges(static_cast<Eigen::Index>(i), 1) = nodes[i + 1];
  }
  return b;
}

// A logically rectangular grid x(i, j), i along, j across; cells counter-clockwise.
Mesh grid_mesh(const std::vector<std::vector<Eigen::Vector2d>>& columns) {
  Mesh mesh;
  const std::size_t ni = columns.size(), nj = columns[0].size();
  mesh.points.resize(static_cast<Eigen::Index>(ni * nj), 2);
  auto id = [&](std::size_t i, std::size_t j) { return static_cast<std::int64_t>(i * nj + j); };
  for (std::size_t i = 0; i < ni; ++i) {
    for (std::size_t j = 0; j < nj; ++j) mesh.points.row(id(i, j)) = columns[i][j].transpose();
  }
  mesh.triangles.resize(0, 3);
  mesh.quads.resize(static_cast<Eigen::Index>((ni - 1) * (nj - 1)), 4);
  Eigen::Index q = 0;
  for (std::size_t i = 0; i + 1 < ni; ++i) {
    for (std::size_t j = 0; j + 1 < nj; ++j) {
      mesh.quads.row(q++) << id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1);
    }
  }
  std::vector<std::int64_t> all(mesh.cell_count());
  for (std::size_t c = 0; c < all.size(); ++c) all[c] = static_cast<std::int64_t>(c);
  mesh.regions["fluid"] = all;
  return mesh;
}

}  // namespace

Mesh build_structured_mesh(const Model& model, double scale, FlowMeshReport& report) {
  const auto& d = model.domain;
  const bool viscous = model.flow.turbulence != "inviscid";
  const double h1 = viscous ? model.flow.first_cell_height * scale : 0.0;
  auto find = [&](const std::string& name) -> const formats::DomainBoundary& {
    for (const auto& b : d.boundaries) {
      if (b.name == name)
        return b;
    }
    throw BadInput("model: domain boundary '" + name + "' missing for domain kind '" + d.settings.kind + "'");
  };
  if (d.settings.kind == "channel") {
    Polyline wall = geometry::reversed(find("wall").points);  // x increasing
    std::vector<double> wx, wy;
    for (const auto& p : wall) {
      wx.push_back(p.x());
      wy.push_back(p.y());
    }
    const int ni = cells(model.mesh.cells_along, 120, scale);
    const int nj = cells(model.mesh.cells_across, 40, scale);
    double min_height = *std::min_element(wy.begin(), wy.end());
    // Clustered towards the wall (j = nj): the fractions run from the wall down to the axis.
    const auto eta = geometric(nj, h1 / min_height);
    std::vector<std::vector<Eigen::Vector2d>> columns;
    for (int i = 0; i <= ni; ++i) {
      const double x = wx.front() + (wx.back() - wx.front()) * i / ni;
      const double y_wall = geometry::interpolate(wx, wy, x);
      std::vector<Eigen::Vector2d> column;
      for (int j = 0; j <= nj; ++j) column.emplace_back(x, y_wall * (1.0 - eta[static_cast<std::size_t>(nj - j)]));
      columns.push_back(column);
    }
    Mesh mesh = grid_mesh(columns);
    const std::size_t nn = static_cast<std::size_t>(nj) + 1;
    std::vector<std::int64_t> sym, out, top, in;
    for (int i = 0; i <= ni; ++i) sym.push_back(static_cast<std::int64_t>(i * nn));
    for (int j = 0; j <= nj; ++j) out.push_back(static_cast<std::int64_t>(ni * nn + j));
    for (int i = ni; i >= 0; --i) top.push_back(static_cast<std::int64_t>(i * nn + nj));
    for (int j = nj; j >= 0; --j) in.push_back(static_cast<std::int64_t>(j));
    // The model names the lower line: `symmetry` (planar) or `axis` (axisymmetric, 2.7).
    const std::string lower = model.geometry == "axisymmetric" ? "axis" : "symmetry";
    mesh.boundaries[lower] = boundary(find(lower).kind, sym);
    mesh.boundaries["outflow"] = boundary("outflow", out);
    mesh.boundaries["wall"] = boundary(find("wall").kind, top);
    mesh.boundaries["inflow"] = boundary("inflow", in);
    report.boundary_layers = 0;
    report.first_layer_height = h1 > 0 ? min_height * eta[1] : 0.0;
    if (report.first_layer_height > 0)
      report.estimated_yplus = estimated_yplus(model, report.first_layer_height);
    return mesh;
  }
  if (d.settings.kind == "flatplate") {
    const double u = d.settings.upstream_length, l = d.settings.plate_length, h = d.settings.farfield_height;
    // Defaults: the TMR 137x97 grid's counts (24 cells ahead of the plate, 112 on it, 96 across).
    const int nu = u > 0 ? cells(model.mesh.cells_upstream, 24, scale) : 0;
    const int nl = cells(model.mesh.cells_along, 112, scale);
    const int nj = cells(model.mesh.cells_across, 96, scale);
    const double le = (model.mesh.leading_edge_spacing > 0 ? model.mesh.leading_edge_spacing : l / (8.0 * nl)) * scale;
    std::vector<double> xs;
    if (nu > 0) {
      const auto t = geometric(nu, le / u);
      for (int i = nu; i > 0; --i) xs.push_back(-u * t[static_cast<std::size_t>(i)]);
    }
    const auto t = geometric(nl, le / l);
    for (int i = 0; i <= nl; ++i) xs.push_back(l * t[static_cast<std::size_t>(i)]);
    const auto eta = geometric(nj, h1 / h);
    std::vector<std::vector<Eigen::Vector2d>> columns;
    for (double x : xs) {
      std::vector<Eigen::Vector2d> column;
      for (int j = 0; j <= nj; ++j) column.emplace_back(x, h * eta[static_cast<std::size_t>(j)]);
      columns.push_back(column);
    }
    Mesh mesh = grid_mesh(columns);
    const std::size_t nn = static_cast<std::size_t>(nj) + 1;
    const int ni = static_cast<int>(xs.size()) - 1;
    std::vector<std::int64_t> sym, plate, out, top, in;
    for (int i = 0; i <= nu; ++i) sym.push_back(static_cast<std::int64_t>(i * nn));
    for (int i = nu; i <= ni; ++i) plate.push_back(static_cast<std::int64_t>(i * nn));
    for (int j = 0; j <= nj; ++j) out.push_back(static_cast<std::int64_t>(ni * nn + j));
    for (int i = ni; i >= 0; --i) top.push_back(static_cast<std::int64_t>(i * nn + nj));
    for (int j = nj; j >= 0; --j) in.push_back(static_cast<std::int64_t>(j));
    if (nu > 0) mesh.boundaries["symmetry"] = boundary("symmetry", sym);
    mesh.boundaries["plate"] = boundary("wall", plate);
    mesh.boundaries["outflow"] = boundary("outflow", out);
    mesh.boundaries["farfield"] = boundary("farfield", top);
    mesh.boundaries["inflow"] = boundary("inflow", in);
    report.boundary_layers = 0;
    report.first_layer_height = h * eta[1];
    report.estimated_yplus = estimated_yplus(model, report.first_layer_height);
    return mesh;
  }
  throw BadInput("domain kind '" + d.settings.kind + "' has no mesher");
}

}  // namespace tfmb::mesh
