#include "mesh.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

namespace tfmb::flow {

int Mesh::boundary_index(std::string_view name) const {
  for (std::size_t b = 0; b < boundaries.size(); ++b) {
    if (boundaries[b].name == name) return static_cast<int>(b);
  }
  return -1;
}

namespace {
std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}
}  // namespace

void check_mesh(const Mesh& mesh) {
  const int n = mesh.num_points();
  std::unordered_map<std::uint64_t, int> edge_cells;
  auto add_cell = [&](const int* ids, int nv, int cell) {
    double twice_area = 0.0;
    for (int k = 0; k < nv; ++k) {
      const int a = ids[k];
      const int b = ids[(k + 1) % nv];
      if (a < 0 || a >= n || b < 0 || b >= n) {
        throw std::invalid_argument("mesh: cell " + std::to_string(cell) + " has node id out of range [0," +
                                    std::to_string(n) + ")");
      }
      const Vec2 pa = mesh.points[a];
      const Vec2 pb = mesh.points[b];
      twice_area += pa.x * pb.y - pb.x * pa.y;
      ++edge_cells[edge_key(a, b)];
    }
    if (!(std::abs(twice_area) > 0.0)) {
      throw std::invalid_argument("mesh: cell " + std::to_string(cell) + " has zero area");
    }
  };
  int cell = 0;
  for (const auto& t : mesh.triangles) add_cell(t.data(), 3, cell++);
  for (const auto& q : mesh.quads) add_cell(q.data(), 4, cell++);

  std::unordered_map<std::uint64_t, int> tagged;
  for (const auto& curve : mesh.boundaries) {
    for (const auto& e : curve.edges) {
      const auto it = edge_cells.find(edge_key(e[0], e[1]));
      if (it == edge_cells.end() || it->second != 1) {
        throw std::invalid_argument("mesh: boundary '" + curve.name + "' edge (" + std::to_string(e[0]) +
                                    "," + std::to_string(e[1]) + ") is not a boundary edge of the cells");
      }
      if (++tagged[it->first] > 1) {
        throw std::invalid_argument("mesh: boundary edge (" + std::to_string(e[0]) + "," +
                                    std::to_string(e[1]) + ") is tagged twice (second time in '" +
                                    curve.name + "')");
      }
    }
  }
  for (const auto& [key, count] : edge_cells) {
    if (count > 2) throw std::invalid_argument("mesh: an edge is shared by more than two cells");
    if (count == 1 && !tagged.count(key)) {
      throw std::invalid_argument("mesh: boundary edge (" + std::to_string(key >> 32) + "," +
                                  std::to_string(key & 0xffffffffu) +
                                  ") belongs to no tagged boundary; tag every boundary curve");
    }
  }
}

}  // namespace tfmb::flow

#include <algorithm>
#include <queue>

namespace tfmb::flow {

namespace {
// The neighbours of each node through the cells' edges, sorted, each once.
std::vector<std::vector<int>> node_neighbours(const Mesh& mesh) {
  std::vector<std::vector<int>> adj(mesh.num_points());
  auto link = [&](const int* ids, int nv) {
    for (int k = 0; k < nv; ++k) {
      const int a = ids[k], b = ids[(k + 1) % nv];
      adj[a].push_back(b);
      adj[b].push_back(a);
    }
  };
  for (const auto& t : mesh.triangles)
    link(t.data(), 3);
  for (const auto& q : mesh.quads)
    link(q.data(), 4);
  for (auto& a : adj) {
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
  }
  return adj;
}
}  // namespace

std::vector<int> rcm_ordering(const Mesh& mesh) {
  const int n = mesh.num_points();
  const std::vector<std::vector<int>> adj = node_neighbours(mesh);
  std::vector<int> order;
  order.reserve(n);
  std::vector<char> seen(n, 0);
  std::vector<int> level(n, -1);
  auto bfs_last = [&](int start) {  // farthest node from start (for a pseudo-peripheral start)
    std::fill(level.begin(), level.end(), -1);
    std::queue<int> q;
    q.push(start);
    level[start] = 0;
    int last = start;
    while (!q.empty()) {
      const int v = q.front();
      q.pop();
      last = v;
      for (int w : adj[v]) {
        if (level[w] < 0) {
          level[w] = level[v] + 1;
          q.push(w);
        }
      }
    }
    return last;
  };
  for (int root = 0; root < n; ++root) {
    if (seen[root]) continue;
    int start = bfs_last(bfs_last(root));
    std::queue<int> q;
    q.push(start);
    seen[start] = 1;
    std::vector<int> next;
    while (!q.empty()) {
      const int v = q.front();
      q.pop();
      order.push_back(v);
      next.clear();
      for (int w : adj[v]) {
        if (!seen[w]) next.push_back(w);
      }
      std::sort(next.begin(), next.end(), [&](int a, int b) {
        return adj[a].size() != adj[b].size() ? adj[a].size() < adj[b].size() : a < b;
      });
      for (int w : next) {
        seen[w] = 1;
        q.push(w);
      }
    }
  }
  std::reverse(order.begin(), order.end());
  std::vector<int> new_of_old(n);
  for (int k = 0; k < n; ++k) new_of_old[order[k]] = k;
  return new_of_old;
}

std::vector<std::vector<int>> strong_coupling_lines(const Mesh& mesh, double ratio) {
  const int n = mesh.num_points();
  const std::vector<std::vector<int>> adj = node_neighbours(mesh);
  std::vector<double> weakest(n, 0.0), anisotropy(n, 0.0);
  auto weight = [&](int a, int b) { return 1.0 / norm(mesh.points[b] - mesh.points[a]); };
  for (int i = 0; i < n; ++i) {
    const auto& a = adj[i];
    double smallest = std::numeric_limits<double>::infinity(), largest = 0.0;
    for (int j : a) {
      smallest = std::min(smallest, weight(i, j));
      largest = std::max(largest, weight(i, j));
    }
    if (!a.empty()) {
      weakest[i] = smallest;
      anisotropy[i] = largest / smallest;
    }
  }
  std::vector<int> seeds(n);
  std::iota(seeds.begin(), seeds.end(), 0);
  std::stable_sort(seeds.begin(), seeds.end(),
                   [&](int a, int b) { return anisotropy[a] > anisotropy[b]; });
  std::vector<char> taken(n, 0);
  // the next node from `from`: its strongest free neighbour, if strong enough
  auto next_of = [&](int from) {
    int best = -1;
    double best_weight = 0.0;
    for (int j : adj[from]) {
      if (!taken[j] && weight(from, j) > best_weight) {
        best = j;
        best_weight = weight(from, j);
      }
    }
    return best_weight >= ratio * weakest[from] ? best : -1;
  };
  std::vector<std::vector<int>> lines;
  for (int seed : seeds) {
    if (taken[seed] || anisotropy[seed] < ratio)
      continue;
    taken[seed] = 1;
    // from the seed along its strongest edge, then the other way from the seed again
    auto grow = [&](std::vector<int>& into) {
      for (int c = next_of(seed); c >= 0; c = next_of(c)) {
        taken[c] = 1;
        into.push_back(c);
      }
    };
    std::vector<int> forward{seed}, backward;
    grow(forward);
    grow(backward);
    if (forward.size() + backward.size() < 2) {
      taken[seed] = 0;  // a single node is no line; it may still join one grown later
      continue;
    }
    std::vector<int> line(backward.rbegin(), backward.rend());
    line.insert(line.end(), forward.begin(), forward.end());
    lines.push_back(std::move(line));
  }
  return lines;
}

std::vector<int> line_ordering(const std::vector<int>& base,
                               const std::vector<std::vector<int>>& lines) {
  const int n = static_cast<int>(base.size());
  std::vector<int> node_at(n);  // the node at each position of `base`
  for (int k = 0; k < n; ++k)
    node_at[base[k]] = k;
  std::vector<int> line_of(n, -1);
  for (std::size_t l = 0; l < lines.size(); ++l) {
    for (int node : lines[l])
      line_of[node] = static_cast<int>(l);
  }
  std::vector<int> new_of_old(n, -1);
  int next = 0;
  for (int k = 0; k < n; ++k) {
    const int node = node_at[k];
    if (new_of_old[node] >= 0)
      continue;
    if (line_of[node] < 0) {
      new_of_old[node] = next++;
      continue;
    }
    const auto& line = lines[line_of[node]];
    if (base[line.front()] <= base[line.back()]) {
      for (int m : line)
        new_of_old[m] = next++;
    } else {
      for (auto it = line.rbegin(); it != line.rend(); ++it)
        new_of_old[*it] = next++;
    }
  }
  return new_of_old;
}

void renumber_nodes(Mesh& mesh, const std::vector<int>& new_of_old) {
  std::vector<Vec2> points(mesh.points.size());
  for (std::size_t k = 0; k < points.size(); ++k) points[new_of_old[k]] = mesh.points[k];
  mesh.points = std::move(points);
  for (auto& t : mesh.triangles) {
    for (int& v : t) v = new_of_old[v];
  }
  for (auto& q : mesh.quads) {
    for (int& v : q) v = new_of_old[v];
  }
  for (auto& c : mesh.boundaries) {
    for (auto& e : c.edges) {
      for (int& v : e) v = new_of_old[v];
    }
  }
}

}  // namespace tfmb::flow
