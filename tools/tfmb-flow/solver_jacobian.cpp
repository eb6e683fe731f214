// Assembly of the implicit operator V/dt + dR/dU: the first-order Jacobian of the edge fluxes
// (the preconditioner of the second-order steps too), the boundary fluxes, the axisymmetric
// source and the strong rows; and the coupled Spalart-Allmaras 5x5 system built on it.
#include <algorithm>
#include <cmath>
#include <vector>

#include "flux_roe.hpp"
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

}  // namespace

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

void FlowSolver::assemble_jacobian(const std::vector<double>& diag_scale) {
  jac_.set_zero();
  if (settings_.turbulent && turbulence_coupled_)
    edge_flux_eddy_slope_.assign(dual_.num_edges(), State{});
  assemble_first_order_fluxes(diag_scale);
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

void FlowSolver::assemble_first_order_fluxes(const std::vector<double>& diag_scale) {
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
    const double time_diagonal = diag_scale[i] + physical_time_diagonal(i);
    for (int m = 0; m < 4; ++m)
      d[5 * m] += time_diagonal;
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
