// FlowSolver's k-omega SST part: the model's state, its eddy viscosity and the segregated
// implicit step of its two equations (turbulence_sst.hpp has the model itself).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "solver.hpp"

namespace tfmb::flow {

namespace {

// The velocity gradient's invariants at node i from its primitive gradient (rho, u, v, p; x and
// y per variable), with the azimuthal strain v/r of an axisymmetric flow (dv/dr on the axis).
sst::Shear node_shear(const std::array<double, 8>& g, const State& w, double r, bool axi) {
  double hoop = 0.0;
  if (axi)
    hoop = r > 0.0 ? w[2] / r : g[5];
  return sst::shear(g[2], g[3], g[4], g[5], hoop);
}

}  // namespace

void FlowSolver::init_sst() {
  if (settings_.turbulence_coupling != TurbulenceCoupling::segregated) {
    throw std::invalid_argument(
        "flow: k-omega SST is solved segregated; --turbulence-coupling coupled or auto is for "
        "Spalart-Allmaras only");
  }
  const int n = dual_.num_nodes;
  sst_k_.assign(n, 0.0);
  sst_omega_.assign(n, 1.0);
  sst_wall_omega_scale_.assign(n, 0.0);
  // omega on a no-slip wall (TMR): 60 nu / (beta1 d1^2), d1 the distance of the nearest node
  // off the wall
  const auto& inc = dual_.node_edges;
  for (int i = 0; i < n; ++i) {
    if (wall_node_bc_[i] < 0)
      continue;
    double d1 = std::numeric_limits<double>::infinity();
    double nearest = std::numeric_limits<double>::infinity();
    for (int k = inc.offsets[i]; k < inc.offsets[i + 1]; ++k) {
      const int j = inc.neighbour[k];
      nearest = std::min(nearest, norm(dual_.coords[j] - dual_.coords[i]));
      if (wall_node_bc_[j] < 0)
        d1 = std::min(d1, wall_distance_[j]);
    }
    if (!std::isfinite(d1))
      d1 = nearest;  // every neighbour on a wall: a corner node
    sst_wall_omega_scale_[i] = 60.0 / (sst::beta1 * d1 * d1);
  }
}

void FlowSolver::set_freestream_sst() {
  for (int i = 0; i < dual_.num_nodes; ++i) {
    const State w = gas_.primitive(u_[i]);
    const double a = gas_.sound_speed(w);
    const double mu = settings_.viscosity.viscosity(gas_.temperature(w));
    sst_k_[i] = sst::freestream_k(a);
    sst_omega_[i] = sst::freestream_omega(w[0], a, mu);
  }
  apply_sst_wall_values();
}

void FlowSolver::apply_sst_wall_values() {
  for (int i = 0; i < dual_.num_nodes; ++i) {
    if (wall_node_bc_[i] < 0)
      continue;
    const State w = gas_.primitive(u_[i]);
    const double nu = settings_.viscosity.viscosity(gas_.temperature(w)) / w[0];
    sst_k_[i] = 0.0;
    sst_omega_[i] = sst_wall_omega_scale_[i] * nu;
  }
}

void FlowSolver::set_sst(const std::vector<double>& k, const std::vector<double>& omega) {
  if (!sst())
    return;
  if (static_cast<int>(k.size()) != dual_.num_nodes ||
      static_cast<int>(omega.size()) != dual_.num_nodes) {
    throw std::invalid_argument("flow: k or omega size differs from mesh");
  }
  for (int i = 0; i < dual_.num_nodes; ++i) {
    if (!(k[i] >= 0.0) || !(omega[i] > 0.0)) {
      throw std::invalid_argument("flow: node " + std::to_string(i) +
                                  " has a non-physical k or omega (k >= 0, omega > 0)");
    }
    sst_k_[new_of_old_[i]] = k[i];
    sst_omega_[new_of_old_[i]] = omega[i];
  }
  apply_sst_wall_values();
}

std::vector<double> FlowSolver::sst_k() const {
  std::vector<double> v;
  if (!sst())
    return v;
  v.resize(sst_k_.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = sst_k_[new_of_old_[i]];
  return v;
}

std::vector<double> FlowSolver::sst_omega() const {
  std::vector<double> v;
  if (!sst())
    return v;
  v.resize(sst_omega_.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = sst_omega_[new_of_old_[i]];
  return v;
}

std::vector<double> FlowSolver::turbulence_snapshot() const {
  if (!sst())
    return nu_tilde_;
  std::vector<double> v(sst_k_);
  v.insert(v.end(), sst_omega_.begin(), sst_omega_.end());
  return v;
}

void FlowSolver::restore_turbulence(const std::vector<double>& snapshot) {
  if (!sst()) {
    nu_tilde_ = snapshot;
    return;
  }
  const auto half = static_cast<std::ptrdiff_t>(sst_k_.size());
  std::copy(snapshot.begin(), snapshot.begin() + half, sst_k_.begin());
  std::copy(snapshot.begin() + half, snapshot.end(), sst_omega_.begin());
}

// mu_t of the current w_, grad_ (the mean-flow gradient of the last residual evaluation) and
// k, omega: rho a1 k / max(a1 omega, S F2) (Omega F2 for SST-V)
void FlowSolver::update_sst_eddy_viscosity() {
  const sst::Constants c = sst::constants(settings_.sst_variant);
  const bool axi = dual_.geometry == Geometry::axisymmetric;
#pragma omp parallel for schedule(static)
  for (int i = 0; i < dual_.num_nodes; ++i) {
    if (wall_node_bc_[i] >= 0) {
      eddy_viscosity_[i] = 0.0;
      continue;
    }
    const State& w = w_[i];
    const double nu = settings_.viscosity.viscosity(gas_.temperature(w)) / w[0];
    const sst::Shear sh = node_shear(grad_[i], w, dual_.coords[i].y, axi);
    const double f2 = sst::blending(c, sst_k_[i], sst_omega_[i], nu, wall_distance_[i], 0.0).f2;
    eddy_viscosity_[i] = sst::eddy_viscosity(w[0], sst_k_[i], sst_omega_[i],
                                             c.vorticity ? sh.vorticity : sh.strain, f2);
  }
}

// One implicit step of each SST equation with the mean flow's local time step, per unit mass
// as for nu_tilde (turbulence_residual()): first-order upwind convection, the diffusion
// (mu + sigma mu_t) / rho between neighbours, the sources at the nodes with their stabilising
// parts implicit; k and omega from the same state, each solved by three ILU(0) defect
// corrections; k = 0 and omega = omega_wall held on no-slip walls.
double FlowSolver::sst_step(double cfl) {
  const int n = dual_.num_nodes;
  const auto& inc = dual_.node_edges;
  const auto& visc = settings_.viscosity;
  const sst::Constants c = sst::constants(settings_.sst_variant);
  const bool axi = dual_.geometry == Geometry::axisymmetric;

  // per node: nu, F1, the two diffusivities and the cross-diffusion product grad k . grad omega
  std::vector<double> nu(n), f1(n), f2(n), diff_k(n), diff_w(n), cross(n);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    Vec2 gk{}, gw{};
    for (int k = inc.offsets[i]; k < inc.offsets[i + 1]; ++k) {
      const int j = inc.neighbour[k];
      gk = gk + (sst_k_[j] - sst_k_[i]) * lsq_.coefficient[k];
      gw = gw + (sst_omega_[j] - sst_omega_[i]) * lsq_.coefficient[k];
    }
    cross[i] = gk.x * gw.x + gk.y * gw.y;
    const double mu = visc.viscosity(gas_.temperature(w_[i]));
    nu[i] = mu / w_[i][0];
    const sst::Blending b =
        wall_node_bc_[i] >= 0
            ? sst::Blending{1.0, 1.0}
            : sst::blending(c, sst_k_[i], sst_omega_[i], nu[i], wall_distance_[i], cross[i]);
    f1[i] = b.f1;
    f2[i] = b.f2;
    diff_k[i] = mu + sst::blend(b.f1, sst::sigma_k1, sst::sigma_k2) * eddy_viscosity_[i];
    diff_w[i] = mu + sst::blend(b.f1, sst::sigma_w1, sst::sigma_w2) * eddy_viscosity_[i];
  }

  std::vector<double> rhs_k(n), rhs_w(n), diag_k(n), diag_w(n);
  std::vector<double> off_k(inc.edge.size()), off_w(inc.edge.size());
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const double time_term = spectral_radius_[i] / cfl;  // V / dt of the mean flow
    double rk = 0.0, rw = 0.0, dk = time_term, dw = time_term;
    for (int k = inc.offsets[i]; k < inc.offsets[i + 1]; ++k) {
      const int e = inc.edge[k];
      const int j = inc.neighbour[k];
      const Vec2 n_e = dual_.edge_normal[e];
      const double vn_out =
          inc.sign[k] * 0.5 * ((w_[i][1] + w_[j][1]) * n_e.x + (w_[i][2] + w_[j][2]) * n_e.y);
      const double inflow = std::max(-vn_out, 0.0);
      const double geometric = norm(n_e) / norm(dual_.coords[j] - dual_.coords[i]);
      const double a_k = inflow + geometric * 0.5 * (diff_k[i] + diff_k[j]) / w_[i][0];
      const double a_w = inflow + geometric * 0.5 * (diff_w[i] + diff_w[j]) / w_[i][0];
      rk += a_k * (sst_k_[j] - sst_k_[i]);
      rw += a_w * (sst_omega_[j] - sst_omega_[i]);
      dk += a_k;
      dw += a_w;
      off_k[k] = -a_k;
      off_w[k] = -a_w;
    }
    if (wall_node_bc_[i] < 0) {
      const double volume = dual_.volume[i];
      const sst::Shear sh = node_shear(grad_[i], w_[i], dual_.coords[i].y, axi);
      const sst::Source src = sst::source(c, sst_k_[i], sst_omega_[i], sh, f1[i], f2[i], cross[i]);
      rk += volume * src.k;
      rw += volume * src.omega;
      dk -= volume * src.k_slope;
      dw -= volume * src.omega_slope;
      if (time_dt_ > 0.0) {
        // physical time derivative by the backward difference of begin_time_step()
        const double* k_n = time_nu_n_.data();
        const double* w_n = k_n + n;
        double dk_dt = time_a_[0] * sst_k_[i] - time_a_[1] * k_n[i];
        double dw_dt = time_a_[0] * sst_omega_[i] - time_a_[1] * w_n[i];
        if (time_a_[2] != 0.0) {
          dk_dt += time_a_[2] * time_nu_nm1_[i];
          dw_dt += time_a_[2] * time_nu_nm1_[n + i];
        }
        rk -= volume * dk_dt / time_dt_;
        rw -= volume * dw_dt / time_dt_;
        dk += physical_time_diagonal(i);
        dw += physical_time_diagonal(i);
      }
    }
    rhs_k[i] = rk;
    rhs_w[i] = rw;
    diag_k[i] = dk;
    diag_w[i] = dw;
  }
  // inflow through inflow, far-field or outflow (backflow) faces brings the free-stream values
  for (const auto& face : dual_.boundary_faces) {
    const int i = face.node;
    State outside;
    const double vn = turbulence_inflow(face, outside);
    if (vn >= 0.0)
      continue;
    const double a = gas_.sound_speed(outside);
    const double mu = visc.viscosity(gas_.temperature(outside));
    rhs_k[i] += -vn * (sst::freestream_k(a) - sst_k_[i]);
    rhs_w[i] += -vn * (sst::freestream_omega(outside[0], a, mu) - sst_omega_[i]);
    diag_k[i] += -vn;
    diag_w[i] += -vn;
  }
  // the residual before the walls' rows are replaced: RMS of dk/dt off the walls
  double sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    if (wall_node_bc_[i] >= 0)
      continue;
    const double r = rhs_k[i] / dual_.volume[i];
    sum2 += r * r;
  }
  for (int i = 0; i < n; ++i) {
    if (wall_node_bc_[i] < 0)
      continue;
    rhs_k[i] = -sst_k_[i];
    rhs_w[i] = sst_wall_omega_scale_[i] * nu[i] - sst_omega_[i];
    diag_k[i] = diag_w[i] = 1.0;
    for (int k = inc.offsets[i]; k < inc.offsets[i + 1]; ++k)
      off_k[k] = off_w[k] = 0.0;
  }
  std::vector<double> delta_k, delta_w;
  solve_scalar(inc, diag_k, off_k, rhs_k, delta_k, 3, sst_ilu_);
  solve_scalar(inc, diag_w, off_w, rhs_w, delta_w, 3, sst_ilu_);
  // physicality-based limits, as for nu_tilde: k falls by at most 90 % and rises by at most
  // max_turbulence_update of k + its free-stream value per step; omega at most halves or
  // doubles, so it stays positive and the eddy viscosity cannot jump by orders in one step
  const double rise = settings_.max_turbulence_update;
  for (int i = 0; i < n; ++i) {
    if (wall_node_bc_[i] >= 0) {
      sst_k_[i] = 0.0;
      sst_omega_[i] = sst_wall_omega_scale_[i] * nu[i];
      continue;
    }
    if (std::isfinite(delta_k[i])) {
      const double scale = sst_k_[i] + sst::freestream_k(gas_.sound_speed(w_[i]));
      sst_k_[i] += std::clamp(delta_k[i], -0.9 * sst_k_[i], rise * scale);
    }
    if (std::isfinite(delta_w[i]))
      sst_omega_[i] += std::clamp(delta_w[i], -0.5 * sst_omega_[i], rise * sst_omega_[i]);
  }
  return std::sqrt(sum2 / n);
}

}  // namespace tfmb::flow
