// Assembly of the implicit operator dR/dU: the first-order Jacobian (edge neighbours) or the
// derivative of the reconstructed second-order fluxes with the limiter held (neighbours of
// neighbours), the boundary fluxes, the axisymmetric source and the strong rows; and the coupled
// Spalart-Allmaras 5x5 system built on it.
#include <algorithm>
#include <cmath>
#include <vector>

#include "flux_roe.hpp"
#include "reconstruction.hpp"
#include "solver.hpp"
#include "turbulence_sa.hpp"

namespace tfmb::flow {

namespace {

// Finite-difference step of conservative variable c of u0 for the Jacobians: relative to the
// variable, with the momentum scale rho c for the momenta (which may be zero).
inline double fd_step(const State& u0, int c) {
  const double scale = (c == 1 || c == 2) ? std::sqrt(u0[0] * u0[3]) : 0.0;
  return 1e-7 * (std::abs(u0[c]) + scale);
}

inline void add_block(double* target, const Block& b, double s) {
  for (int k = 0; k < 16; ++k)
    target[k] += s * b[k];
}

// a b (4x4, row-major)
Block multiply(const Block& a, const Block& b) {
  Block c{};
  for (int r = 0; r < 4; ++r) {
    for (int k = 0; k < 4; ++k) {
      const double s = a[4 * r + k];
      for (int q = 0; q < 4; ++q)
        c[4 * r + q] += s * b[4 * k + q];
    }
  }
  return c;
}

// target += s a diag(column_scale)
void add_scaled_columns(Block& target, const Block& a, const State& column_scale, double s) {
  for (int r = 0; r < 4; ++r) {
    for (int q = 0; q < 4; ++q)
      target[4 * r + q] += s * a[4 * r + q] * column_scale[q];
  }
}

}  // namespace

std::vector<std::array<int, 2>> second_neighbour_pairs(const DualMesh& dual) {
  // residual i depends on the states of i's neighbours and, through their gradients, of
  // theirs: the pairs at graph distance 1 or 2, each once (smaller node first)
  const auto& inc = dual.node_edges;
  std::vector<std::array<int, 2>> pairs;
  std::vector<int> reached;
  for (int i = 0; i < dual.num_nodes; ++i) {
    reached.clear();
    for (int k = inc.offsets[i]; k < inc.offsets[i + 1]; ++k) {
      const int j = inc.neighbour[k];
      reached.push_back(j);
      for (int kk = inc.offsets[j]; kk < inc.offsets[j + 1]; ++kk)
        reached.push_back(inc.neighbour[kk]);
    }
    std::sort(reached.begin(), reached.end());
    reached.erase(std::unique(reached.begin(), reached.end()), reached.end());
    for (int m : reached) {
      if (m > i)
        pairs.push_back({i, m});
    }
  }
  return pairs;
}

BlockSparseMatrix FlowSolver::jacobian_pattern(int block_size) const {
  return second_order_jacobian_
             ? make_pattern(dual_.num_nodes, second_neighbour_pairs(dual_), block_size)
             : make_pattern(dual_.num_nodes, dual_.edges, block_size);
}

void FlowSolver::viscous_edge_jacobian(int e, Block& left, Block& right) {
  const int i = dual_.edges[e][0];
  const int j = dual_.edges[e][1];
  const Vec2 n_e = dual_.edge_normal[e];
  double c = 0.0;
  const bool axi = dual_.geometry == Geometry::axisymmetric;
  const double mu_t = settings_.turbulent ? 0.5 * (eddy_viscosity_[i] + eddy_viscosity_[j]) : 0.0;
  const State fv0 =
      viscous_flux(gas_, settings_.viscosity, dual_.coords[i], dual_.coords[j], w_[i], w_[j],
                   grad_[i], grad_[j], axi ? n_e : dual_.edge_normal_planar[e],
                   axi ? norm(n_e) / norm(dual_.edge_normal_planar[e]) : 0.0, &c, mu_t);
  const double uf = 0.5 * (w_[i][1] + w_[j][1]);
  const double vf = 0.5 * (w_[i][2] + w_[j][2]);
  const double mu_laminar =
      settings_.viscosity.viscosity(0.5 * (gas_.temperature(w_[i]) + gas_.temperature(w_[j])));
  const double eddy_fraction = mu_t / (mu_laminar + mu_t);
  if (settings_.turbulent && turbulence_coupled_) {
    // f = F_c - F_v and F_v is affine in mu_t: one difference is its exact slope
    const double h = mu_laminar;
    const State fv1 =
        viscous_flux(gas_, settings_.viscosity, dual_.coords[i], dual_.coords[j], w_[i], w_[j],
                     grad_[i], grad_[j], axi ? n_e : dual_.edge_normal_planar[e],
                     axi ? norm(n_e) / norm(dual_.edge_normal_planar[e]) : 0.0, nullptr, mu_t + h);
    for (int v = 0; v < 4; ++v)
      edge_flux_eddy_slope_[e][v] = -(fv1[v] - fv0[v]) / h;
  }
  // F = F_c - c (Phi_j - Phi_i)
  left = viscous_phi_jacobian(gas_, settings_.viscosity, w_[i], uf, vf, eddy_fraction);
  right = viscous_phi_jacobian(gas_, settings_.viscosity, w_[j], uf, vf, eddy_fraction);
  for (int k = 0; k < 16; ++k) {
    left[k] *= c;
    right[k] *= -c;
  }
}

void FlowSolver::assemble_jacobian(const std::vector<double>& diag_scale, bool reconstructed) {
  jac_.set_zero();
  if (settings_.turbulent && turbulence_coupled_)
    edge_flux_eddy_slope_.assign(dual_.num_edges(), State{});
  if (reconstructed)
    assemble_reconstructed_fluxes();
  else
    assemble_first_order_fluxes();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < dual_.num_nodes; ++i) {
    double* d = jac_.block(jac_.diag_pos[i]);
    const double time_diagonal = diag_scale[i] + physical_time_diagonal(i);
    for (int m = 0; m < 4; ++m)
      d[5 * m] += time_diagonal;
  }
  if (dual_.geometry == Geometry::axisymmetric) {
    const double g1 = gas_.gamma - 1.0;
    for (int i = 0; i < dual_.num_nodes; ++i) {
      const State& w = w_[i];
      double* d = jac_.block(jac_.diag_pos[i]);
      const double a = dual_.area[i];
      // d p / d U (Blazek 2015, eq. A.4)
      d[8] -= a * g1 * 0.5 * (w[1] * w[1] + w[2] * w[2]);
      d[9] -= a * -g1 * w[1];
      d[10] -= a * -g1 * w[2];
      d[11] -= a * g1;
      const double r = dual_.coords[i].y;
      if (settings_.viscous && r > 1e-12) {
        // + d(tau_theta_theta A)/dU through its 4/3 mu v / r part
        const double k = a * 4.0 / 3.0 *
                         (settings_.viscosity.viscosity(gas_.temperature(w)) + eddy_viscosity_[i]) /
                         (r * w[0]);
        d[8] -= k * w[2];
        d[10] += k;
      }
    }
  }
  // Strong no-slip rows: the update of the wall velocity (and temperature) is fixed.
  for (int i = 0; i < dual_.num_nodes; ++i) {
    if (fixed_node_[i]) {
      for (int p = jac_.row_ptr[i]; p < jac_.row_ptr[i + 1]; ++p)
        std::fill(jac_.block(p), jac_.block(p) + 16, 0.0);
      double* d = jac_.block(jac_.diag_pos[i]);
      for (int m = 0; m < 4; ++m)
        d[5 * m] = 1.0;
      continue;
    }
    const int b = wall_node_bc_[i];
    if (b < 0)
      continue;
    const bool iso = bcs_[b].kind == BcKind::wall_isothermal;
    for (int p = jac_.row_ptr[i]; p < jac_.row_ptr[i + 1]; ++p) {
      double* blk = jac_.block(p);
      for (int r = 1; r < (iso ? 4 : 3); ++r) {
        for (int c = 0; c < 4; ++c)
          blk[4 * r + c] = 0.0;
      }
    }
    double* d = jac_.block(jac_.diag_pos[i]);
    d[5] = 1.0;
    d[10] = 1.0;
    if (iso) {
      d[12] = -gas_.cv() * wall_temperature_at(b, i);
      d[15] = 1.0;
    }
  }
}

void FlowSolver::assemble_first_order_fluxes() {
  const int ne = dual_.num_edges();
  const bool viscous = settings_.viscous;
#pragma omp parallel for schedule(static)
  for (int e = 0; e < ne; ++e) {
    const int i = dual_.edges[e][0];
    const int j = dual_.edges[e][1];
    const Vec2 n_e = dual_.edge_normal[e];
    RoeFluxJacobians jac;
    if (exact_roe_jacobian_) {
      roe_flux_exact(gas_, w_[i], w_[j], n_e.x, n_e.y, settings_.entropy_fix, jac);
    } else {
      roe_flux(gas_, w_[i], w_[j], n_e.x, n_e.y, settings_.entropy_fix, &jac);
    }
    if (viscous) {
      Block left, right;
      viscous_edge_jacobian(e, left, right);
      add_block(jac.d_left.data(), left, 1.0);
      add_block(jac.d_right.data(), right, 1.0);
    }
    // R_i += F, R_j -= F
    double* bij = jac_.block(edge_pos_ij_[e]);
    double* bji = jac_.block(edge_pos_ji_[e]);
    for (int k = 0; k < 16; ++k) {
      bij[k] = jac.d_right[k];
      bji[k] = -jac.d_left[k];
    }
  }
  // Diagonal: conservation makes dR_i/dU_i = -sum_j dR_j/dU_i over the edges of i.
  const auto& inc = dual_.node_edges;
#pragma omp parallel for schedule(static)
  for (int i = 0; i < dual_.num_nodes; ++i) {
    double* d = jac_.block(jac_.diag_pos[i]);
    for (int k = inc.offsets[i]; k < inc.offsets[i + 1]; ++k) {
      const int e = inc.edge[k];
      const double* b = jac_.block(inc.sign[k] > 0 ? edge_pos_ji_[e] : edge_pos_ij_[e]);
      for (int m = 0; m < 16; ++m)
        d[m] -= b[m];
    }
  }
  // Boundary fluxes: forward differences in the conservative variables of the face node.
  for (const auto& face : dual_.boundary_faces) {
    const BoundaryCondition& bc = bcs_[face.curve];
    double* d = jac_.block(jac_.diag_pos[face.node]);
    const State& u0 = u_[face.node];
    const State f0 =
        boundary_flux(gas_, bc, w_[face.node], face.normal, face.node, settings_.entropy_fix);
    for (int c = 0; c < 4; ++c) {
      State up = u0;
      const double h = fd_step(u0, c);
      up[c] += h;
      const State f1 = boundary_flux(gas_, bc, gas_.primitive(up), face.normal, face.node,
                                     settings_.entropy_fix);
      for (int r = 0; r < 4; ++r)
        d[4 * r + c] += (f1[r] - f0[r]) / h;
    }
  }
}

// f(column, dW_face/dW_column per variable) for the state of node a reconstructed along h: the
// node itself and each of its gradient's neighbours.
template <class F>
void FlowSolver::for_each_reconstruction_weight(int a, Vec2 h, F&& f) const {
  const auto& inc = dual_.node_edges;
  State self{1.0, 1.0, 1.0, 1.0};
  for (int k = inc.offsets[a]; k < inc.offsets[a + 1]; ++k) {
    const Vec2 c = recon_lsq_.coefficient[k];
    const double ch = c.x * h.x + c.y * h.y;
    State weight;
    for (int v = 0; v < 4; ++v) {
      weight[v] = (settings_.limiter ? phi_[a][v] : 1.0) * ch;
      self[v] -= weight[v];
    }
    f(inc.neighbour[k], weight);
  }
  f(a, self);
}

// The reconstructed fluxes' derivative with the limiter held at phi_ (Blazek 2015, sec. 6.2.4,
// for the idea; here exact but for the limiter and keep_positive). An edge's flux f(W_L, W_R)
// sees the node states through W_L = W_a + phi_a (grad W_a . h_a) with
// grad W_a = sum_k c_k (W_k - W_a) (gradient_lsq.hpp), so
//   dW_L/dW_k = phi_a (c_k . h_a)   per variable, for each neighbour k of a,
//   dW_L/dW_a = 1 - sum_k phi_a (c_k . h_a),
// and dR_i/dU_m = sum over i's edges of sign (df/dW_L dW_L/dW_m + df/dW_R dW_R/dW_m) dW/dU(W_m).
// The viscous flux keeps its thin-shear Jacobian against the two edge nodes, as at first order.
void FlowSolver::assemble_reconstructed_fluxes() {
  const int n = dual_.num_nodes;
  const int ne = dual_.num_edges();
  const bool viscous = settings_.viscous;
  const bool limit = settings_.limiter;
  const auto& rgrad = recon_mapped_ ? recon_grad_ : grad_;
  const auto& inc = dual_.node_edges;
  // phase 1, per edge: df/dW_L and df/dW_R at the reconstructed states, and the viscous blocks
  // in primitive variables of the edge nodes
  edge_jacobian_left_.resize(ne);
  edge_jacobian_right_.resize(ne);
  if (viscous) {
    edge_viscous_left_.resize(ne);
    edge_viscous_right_.resize(ne);
  }
#pragma omp parallel for schedule(static)
  for (int e = 0; e < ne; ++e) {
    const int i = dual_.edges[e][0];
    const int j = dual_.edges[e][1];
    const Vec2 n_e = dual_.edge_normal[e];
    const State wl = reconstruct(w_[i], rgrad[i], limit ? &phi_[i] : nullptr, recon_half_ij_[e]);
    const State wr = reconstruct(w_[j], rgrad[j], limit ? &phi_[j] : nullptr, recon_half_ji_[e]);
    RoeFluxJacobians jac;
    if (exact_roe_jacobian_)
      roe_flux_exact(gas_, wl, wr, n_e.x, n_e.y, settings_.entropy_fix, jac);
    else
      roe_flux(gas_, wl, wr, n_e.x, n_e.y, settings_.entropy_fix, &jac);
    edge_jacobian_left_[e] = multiply(jac.d_left, gas_.conservative_jacobian(wl));
    edge_jacobian_right_[e] = multiply(jac.d_right, gas_.conservative_jacobian(wr));
    if (viscous) {
      Block left, right;
      viscous_edge_jacobian(e, left, right);
      edge_viscous_left_[e] = multiply(left, gas_.conservative_jacobian(w_[i]));
      edge_viscous_right_[e] = multiply(right, gas_.conservative_jacobian(w_[j]));
    }
  }
  // phase 2, per row (no two threads write one row): sum the primitive-variable blocks of each
  // column, then turn them into conservative ones
  constexpr State kOnes{1.0, 1.0, 1.0, 1.0};
#pragma omp parallel
  {
    std::vector<Block> row;
#pragma omp for schedule(static)
    for (int i = 0; i < n; ++i) {
      const int first = jac_.row_ptr[i];
      const int last = jac_.row_ptr[i + 1];
      row.assign(last - first, Block{});
      const auto add = [&](int column, const Block& a, const State& scale, double s) {
        const int* c = std::lower_bound(jac_.col.data() + first, jac_.col.data() + last, column);
        add_scaled_columns(row[c - (jac_.col.data() + first)], a, scale, s);
      };
      // one side of an edge flux: node `a` reconstructed along h with the flux's derivative p
      const auto add_side = [&](const Block& p, int a, Vec2 h, double s) {
        for_each_reconstruction_weight(
            a, h, [&](int column, const State& weight) { add(column, p, weight, s); });
      };
      for (int k = inc.offsets[i]; k < inc.offsets[i + 1]; ++k) {
        const int e = inc.edge[k];
        const double s = inc.sign[k];  // R_i += s f_e
        const int a = dual_.edges[e][0];
        const int b = dual_.edges[e][1];
        add_side(edge_jacobian_left_[e], a, recon_half_ij_[e], s);
        add_side(edge_jacobian_right_[e], b, recon_half_ji_[e], s);
        if (viscous) {
          add(a, edge_viscous_left_[e], kOnes, s);
          add(b, edge_viscous_right_[e], kOnes, s);
        }
      }
      for (int p = first; p < last; ++p) {
        const Block conservative =
            multiply(row[p - first], gas_.primitive_jacobian(w_[jac_.col[p]]));
        std::copy(conservative.begin(), conservative.end(), jac_.block(p));
      }
    }
  }
  // Boundary fluxes of the face states reconstructed like the edge states: forward differences
  // in the conservative variables of the face state, then the same chain.
  for (std::size_t face_index = 0; face_index < dual_.boundary_faces.size(); ++face_index) {
    const auto& face = dual_.boundary_faces[face_index];
    const BoundaryCondition& bc = bcs_[face.curve];
    const int a = face.node;
    const State wf = reconstruct(w_[a], rgrad[a], limit ? &phi_[a] : nullptr,
                                 recon_stencil_.to_face[face_index]);
    const State uf = gas_.conservative(wf);
    const State f0 = boundary_flux(gas_, bc, wf, face.normal, a, settings_.entropy_fix);
    Block d_flux{};  // df/dU_f
    for (int c = 0; c < 4; ++c) {
      State up = uf;
      const double h = fd_step(uf, c);
      up[c] += h;
      const State f1 =
          boundary_flux(gas_, bc, gas_.primitive(up), face.normal, a, settings_.entropy_fix);
      for (int r = 0; r < 4; ++r)
        d_flux[4 * r + c] = (f1[r] - f0[r]) / h;
    }
    const Block p = multiply(d_flux, gas_.conservative_jacobian(wf));
    const Vec2 h = recon_stencil_.to_face[face_index];
    const auto add = [&](int column, const State& scale) {
      Block scaled{};
      add_scaled_columns(scaled, p, scale, 1.0);
      add_block(jac_.block(jac_.find(a, column)),
                multiply(scaled, gas_.primitive_jacobian(w_[column])), 1.0);
    };
    for_each_reconstruction_weight(a, h, add);
  }
}

void FlowSolver::assemble_coupled_jacobian() {
  const int n = dual_.num_nodes;
  const auto& inc = dual_.node_edges;
  std::vector<double> eddy_slope(n);
  for (int i = 0; i < n; ++i)
    eddy_slope[i] = sa::eddy_viscosity_derivative(w_[i][0], nu_tilde_[i], sa_nu_[i]);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    for (int p = jac_.row_ptr[i]; p < jac_.row_ptr[i + 1]; ++p) {
      const double* a = jac_.block(p);
      double* c = jac_coupled_.block(p);
      for (int r = 0; r < 4; ++r) {
        for (int q = 0; q < 4; ++q)
          c[5 * r + q] = a[4 * r + q];
        c[5 * r + 4] = 0.0;
      }
      for (int q = 0; q < 5; ++q)
        c[20 + q] = 0.0;
    }
    double* diag = jac_coupled_.block(jac_coupled_.diag_pos[i]);
    diag[24] = sa_row_scale_ * sa_diag_[i];
    for (int q = 0; q < 4; ++q)
      diag[20 + q] = sa_row_scale_ * sa_cross_diag_[4 * static_cast<std::size_t>(i) + q];
    // mean-flow rows against nu_tilde: R_i = sum_e sign f_e, f_e through mu_t,face =
    // (mu_t,i + mu_t,j) / 2
    const double slope_i = 0.5 * eddy_slope[i];
    for (int k = inc.offsets[i]; k < inc.offsets[i + 1]; ++k) {
      const int e = inc.edge[k];
      const int j = inc.neighbour[k];
      const int pos = inc.sign[k] > 0 ? edge_pos_ij_[e] : edge_pos_ji_[e];
      double* off = jac_coupled_.block(pos);
      off[24] = sa_row_scale_ * sa_offdiag_[k];
      for (int q = 0; q < 4; ++q)
        off[20 + q] = sa_row_scale_ * sa_cross_offdiag_[4 * static_cast<std::size_t>(k) + q];
      const State& df = edge_flux_eddy_slope_[e];
      const double s = inc.sign[k];
      for (int r = 0; r < 4; ++r) {
        diag[5 * r + 4] += s * df[r] * slope_i;
        off[5 * r + 4] += s * df[r] * 0.5 * eddy_slope[j];
      }
    }
    // rows replaced by strong conditions (no-slip momentum and temperature, imposed nodes)
    // do not depend on nu_tilde
    const int b = wall_node_bc_[i];
    const int rows_fixed_from = fixed_node_[i] ? 0 : 1;
    const int rows_fixed_to =
        fixed_node_[i] ? 4 : (b < 0 ? 1 : (bcs_[b].kind == BcKind::wall_isothermal ? 4 : 3));
    for (int p = jac_coupled_.row_ptr[i]; p < jac_coupled_.row_ptr[i + 1]; ++p) {
      for (int r = rows_fixed_from; r < rows_fixed_to; ++r)
        jac_coupled_.block(p)[5 * r + 4] = 0.0;
    }
  }
}

}  // namespace tfmb::flow
