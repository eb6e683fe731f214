#include "solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>

#include "flux_roe.hpp"
#include "limiter.hpp"
#include "reconstruction.hpp"
#include "scalar_ilu.hpp"
#include "turbulence_sa.hpp"
#include "wall_distance.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace tfmb::flow {

namespace {

// Sets the OpenMP thread count of the calling thread for one solver call, then restores it.
class ScopedThreads {
 public:
  explicit ScopedThreads(int threads) {
#ifdef _OPENMP
    previous_ = omp_get_max_threads();
    omp_set_num_threads(std::max(threads, 1));
#else
    (void)threads;
#endif
  }
  ~ScopedThreads() {
#ifdef _OPENMP
    omp_set_num_threads(previous_);
#endif
  }
  ScopedThreads(const ScopedThreads&) = delete;
  ScopedThreads& operator=(const ScopedThreads&) = delete;

 private:
  int previous_ = 1;
};

// A linear solve that leaves more than this fraction of its initial residual failed: the step
// it gives is little more than a guess (see update_cfl() and accept_or_reject_step()).
constexpr double kLinearSolveFailed = 0.5;

// Newton-Krylov phases of MatrixFree::after_limiter_freeze that may fail before a run stays
// with defect correction and a live limiter
constexpr int kNewtonFallbacks = 3;
// A march that has diverged (DivergedMarch) goes back to its best state with half the CFL
// ceiling, at most kBestStateRestarts times
constexpr int kBestStateRestarts = 4;

// Smallest pressure accepted, relative to the total energy per volume rho E (see physical()).
constexpr double kPressureFloor = 1e-10;

}  // namespace

FlowSolver::FlowSolver(const Mesh& mesh, Geometry geometry, const PerfectGas& gas,
                       std::vector<BoundaryCondition> bcs, const SolverSettings& settings)
    : mesh_(mesh), gas_(gas), bcs_(std::move(bcs)), settings_(settings) {
  check_mesh(mesh_);
  exact_roe_jacobian_ = exact_roe_jacobian_by_settings();
  coords_external_ = mesh.points;
  new_of_old_.resize(mesh_.points.size());
  for (std::size_t k = 0; k < new_of_old_.size(); ++k)
    new_of_old_[k] = static_cast<int>(k);
  if (settings_.renumber) {
    new_of_old_ = rcm_ordering(mesh_);
    if (settings_.renumber_lines) {
      const auto lines = strong_coupling_lines(mesh_);
      new_of_old_ = line_ordering(new_of_old_, lines);
      ordering_lines_ = static_cast<int>(lines.size());
      for (const auto& line : lines)
        ordering_line_nodes_ += static_cast<int>(line.size());
    }
    renumber_nodes(mesh_, new_of_old_);
  }
  old_of_new_.resize(new_of_old_.size());
  for (std::size_t k = 0; k < new_of_old_.size(); ++k)
    old_of_new_[new_of_old_[k]] = static_cast<int>(k);
  for (auto& bc : bcs_) {
    if (bc.node_freestream.empty())
      continue;
    if (bc.node_freestream.size() != new_of_old_.size()) {
      throw std::invalid_argument("flow: node_freestream size differs from the number of nodes");
    }
    std::vector<State> internal(bc.node_freestream.size());
    for (std::size_t k = 0; k < internal.size(); ++k)
      internal[new_of_old_[k]] = bc.node_freestream[k];
    bc.node_freestream = std::move(internal);
  }
  if (bcs_.size() != mesh_.boundaries.size()) {
    throw std::invalid_argument("flow: " + std::to_string(bcs_.size()) +
                                " boundary conditions for " +
                                std::to_string(mesh_.boundaries.size()) + " boundary curves");
  }
  dual_ = build_dual(mesh_, geometry);
  lsq_ = build_lsq_gradient(dual_);
  {
    std::vector<char> wall_curves(bcs_.size(), 0);
    for (std::size_t b = 0; b < bcs_.size(); ++b) {
      wall_curves[b] = bcs_[b].kind == BcKind::slip_wall || bcs_[b].no_slip();
    }
    if (settings_.order >= 2 && settings_.wall_aligned_aspect_ratio > 0.0) {
      recon_stencil_ = wall_aligned_stencil(
          mesh_, dual_, wall_curves, settings_.wall_aligned_aspect_ratio, &recon_mapped_nodes_);
    } else {
      recon_stencil_ = cartesian_stencil(dual_);
    }
    recon_mapped_ = recon_mapped_nodes_ > 0;
    recon_lsq_ = recon_mapped_ ? build_lsq_gradient(dual_, recon_stencil_.to_neighbour) : lsq_;
    const auto& inc = dual_.node_edges;
    recon_half_ij_.resize(dual_.num_edges());
    recon_half_ji_.resize(dual_.num_edges());
    for (int i = 0; i < dual_.num_nodes; ++i) {
      for (int k = inc.offsets[i]; k < inc.offsets[i + 1]; ++k) {
        const Vec2 half = 0.5 * recon_stencil_.to_neighbour[k];
        (inc.sign[k] > 0.0 ? recon_half_ij_ : recon_half_ji_)[inc.edge[k]] = half;
      }
    }
  }
  venkat_eps_ = make_venkat_epsilon(dual_, settings_.venkat_k, settings_.reference_state);
  jac_ = make_pattern(dual_.num_nodes, dual_.edges);
  edge_pos_ij_.resize(dual_.num_edges());
  edge_pos_ji_.resize(dual_.num_edges());
  for (int e = 0; e < dual_.num_edges(); ++e) {
    edge_pos_ij_[e] = jac_.find(dual_.edges[e][0], dual_.edges[e][1]);
    edge_pos_ji_[e] = jac_.find(dual_.edges[e][1], dual_.edges[e][0]);
  }
  // No-slip nodes: walls win over any other boundary meeting them at a corner.
  wall_node_bc_.assign(dual_.num_nodes, -1);
  for (int b = 0; b < static_cast<int>(bcs_.size()); ++b) {
    if (!bcs_[b].no_slip())
      continue;
    if (!settings_.viscous) {
      throw std::invalid_argument("flow: boundary '" + mesh_.boundaries[b].name +
                                  "' is a no-slip wall but the solver is inviscid; use slip_wall");
    }
    for (const auto& e : mesh_.boundaries[b].edges) {
      for (int node : e) {
        if (wall_node_bc_[node] < 0 || bcs_[b].kind == BcKind::wall_isothermal)
          wall_node_bc_[node] = b;
      }
    }
  }
  fixed_node_.assign(dual_.num_nodes, 0);
  fixed_u_.assign(dual_.num_nodes, State{});
  {
    std::vector<Vec2> normal_sum(dual_.num_nodes);
    for (const auto& face : dual_.boundary_faces) {
      if (bcs_[face.curve].kind == BcKind::farfield)
        normal_sum[face.node] = normal_sum[face.node] + face.normal;
    }
    for (const auto& face : dual_.boundary_faces) {
      const BoundaryCondition& bc = bcs_[face.curve];
      if (bc.kind != BcKind::farfield)
        continue;
      const State& inf = bc.node_freestream.empty() ? bc.freestream : bc.node_freestream[face.node];
      const Vec2 nsum = normal_sum[face.node];
      const double vn = (inf[1] * nsum.x + inf[2] * nsum.y) / norm(nsum);
      if (vn <= -gas_.sound_speed(inf)) {
        fixed_node_[face.node] = 1;
        fixed_u_[face.node] = gas_.conservative(inf);
        wall_node_bc_[face.node] = -1;
      }
    }
  }
  const int n = dual_.num_nodes;
  for (int i = 0; i < n; ++i) {
    if (fixed_node_[i] || wall_node_bc_[i] >= 0)
      assembled_rows_.push_back(i);
  }
  u_.assign(n, State{});
  w_.assign(n, State{});
  res_.assign(n, State{});
  phi_.assign(n, State{1.0, 1.0, 1.0, 1.0});
  grad_.assign(n, std::array<double, 8>{});
  edge_flux_.assign(dual_.num_edges(), State{});
  spectral_radius_.assign(n, 0.0);
  eddy_viscosity_.assign(n, 0.0);
  if (settings_.turbulent) {
    if (!settings_.viscous)
      throw std::invalid_argument("flow: a turbulence model needs the viscous terms");
    std::vector<std::array<Vec2, 2>> walls;
    for (int b = 0; b < static_cast<int>(bcs_.size()); ++b) {
      if (!bcs_[b].no_slip())
        continue;
      for (const auto& e : mesh_.boundaries[b].edges)
        walls.push_back({dual_.coords[e[0]], dual_.coords[e[1]]});
    }
    wall_distance_ = tfmb::flow::wall_distance(dual_.coords, walls);
    if (sst()) {
      init_sst();
      return;
    }
    nu_tilde_.assign(n, 0.0);
    sa_row_scale_ = settings_.reference_state[0];
    if (settings_.turbulence_coupling != TurbulenceCoupling::segregated)
      jac_coupled_ = make_pattern(dual_.num_nodes, dual_.edges, 5);
    turbulence_coupled_ = settings_.turbulence_coupling == TurbulenceCoupling::coupled;
  } else {
    settings_.turbulence_coupling = TurbulenceCoupling::segregated;  // nothing to couple
  }
}

double FlowSolver::wall_temperature_at(int b, int node) const {
  const auto& per_node = bcs_[b].node_wall_temperature;
  return per_node.empty() ? bcs_[b].wall_temperature : per_node[node];
}

void FlowSolver::make_walls_isothermal(double below) {
  for (int i = 0; i < dual_.num_nodes; ++i)
    w_[i] = gas_.primitive(u_[i]);
  for (int b = 0; b < static_cast<int>(bcs_.size()); ++b) {
    if (bcs_[b].kind != BcKind::wall_adiabatic)
      continue;
    bcs_[b].kind = BcKind::wall_isothermal;
    bcs_[b].node_wall_temperature.assign(dual_.num_nodes, 0.0);
    for (const auto& e : mesh_.boundaries[b].edges) {
      for (int node : e)
        bcs_[b].node_wall_temperature[node] = gas_.temperature(w_[node]) - below;
    }
  }
  apply_strong_conditions(u_);
}

void FlowSolver::set_freestream_nu_tilde() {
  if (!settings_.turbulent || sst())
    return;
  for (int i = 0; i < dual_.num_nodes; ++i) {
    const State w = gas_.primitive(u_[i]);
    const double nu = settings_.viscosity.viscosity(gas_.temperature(w)) / w[0];
    nu_tilde_[i] = wall_node_bc_[i] >= 0 ? 0.0 : settings_.sa_freestream_ratio * nu;
  }
}

void FlowSolver::set_nu_tilde(const std::vector<double>& nu_tilde) {
  if (!settings_.turbulent || sst())
    return;
  if (static_cast<int>(nu_tilde.size()) != dual_.num_nodes) {
    throw std::invalid_argument("flow: nu_tilde size differs from mesh");
  }
  for (int i = 0; i < dual_.num_nodes; ++i) {
    nu_tilde_[new_of_old_[i]] = wall_node_bc_[new_of_old_[i]] >= 0 ? 0.0 : nu_tilde[i];
  }
}

std::vector<double> FlowSolver::nu_tilde() const {
  std::vector<double> v;
  if (!settings_.turbulent || sst())
    return v;
  v.resize(nu_tilde_.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = nu_tilde_[new_of_old_[i]];
  return v;
}

std::vector<double> FlowSolver::eddy_viscosity() {
  for (int i = 0; i < dual_.num_nodes; ++i)
    w_[i] = gas_.primitive(u_[i]);
  update_eddy_viscosity();
  std::vector<double> v(eddy_viscosity_.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = eddy_viscosity_[new_of_old_[i]];
  return v;
}

std::vector<double> FlowSolver::wall_distance() const {
  std::vector<double> v;
  if (!settings_.turbulent)
    return v;
  v.resize(wall_distance_.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = wall_distance_[new_of_old_[i]];
  return v;
}

void FlowSolver::update_eddy_viscosity() {
  if (!settings_.turbulent)
    return;
  if (sst()) {
    update_sst_eddy_viscosity();
    return;
  }
#pragma omp parallel for schedule(static)
  for (int i = 0; i < dual_.num_nodes; ++i) {
    const double mu = settings_.viscosity.viscosity(gas_.temperature(w_[i]));
    eddy_viscosity_[i] = sa::eddy_viscosity(w_[i][0], nu_tilde_[i], mu / w_[i][0]);
  }
}

void FlowSolver::turbulence_residual(bool jacobian, const std::vector<double>* diag_scale) {
  // The nu_tilde equation in non-conservative form (TMR "SA"):
  //   D nu_tilde/Dt = P - D + 1/sigma [div((nu + nu_tilde) grad nu_tilde) + cb2 |grad nu_tilde|^2],
  // the diffusion split as (1 + cb2)/sigma div(D grad nu_tilde) - cb2/sigma D_i lap(nu_tilde)
  // (Spalart and Allmaras 1994; the edge form used by FUN3D), first-order upwind convection.
  // rhs = V d nu_tilde / dt = -sa_res_; the matrix V/dt - d rhs / d nu_tilde is an M-matrix.
  const int n = dual_.num_nodes;
  const auto& visc = settings_.viscosity;
  const auto& inc = dual_.node_edges;
  sa_res_.resize(n);
  sa_nu_.resize(n);
  sa_diffusivity_.resize(n);
  const bool cross = jacobian && turbulence_coupled_;
  // sized here and zeroed in the threaded loops below (a serial assign was 0.2 % of a two-thread
  // run on nasa-2dcd's case mesh): the diagonals where they are set, the off-diagonals per row
  if (jacobian) {
    sa_diag_.resize(n);
    sa_offdiag_.resize(inc.edge.size());
  }
  if (cross) {
    sa_cross_diag_.resize(4 * static_cast<std::size_t>(n));
    sa_cross_offdiag_.resize(4 * inc.edge.size());
  }
  std::vector<double>& nu = sa_nu_;
  std::vector<double>& diffusivity = sa_diffusivity_;
  const bool exact = settings_.sa_exact_jacobian;
  std::vector<double> diffusivity_slope(exact ? n : 0);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    nu[i] = visc.viscosity(gas_.temperature(w_[i])) / w_[i][0];
    diffusivity[i] = sa::diffusivity(nu_tilde_[i], nu[i]);
    if (exact)
      diffusivity_slope[i] = sa::diffusivity_derivative(nu_tilde_[i], nu[i]);
  }
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    double r = 0.0, d = diag_scale ? (*diag_scale)[i] : 0.0;
    if (cross) {
      std::fill_n(sa_cross_diag_.data() + 4 * static_cast<std::size_t>(i), 4, 0.0);
      std::fill(sa_cross_offdiag_.data() + 4 * static_cast<std::size_t>(inc.offsets[i]),
                sa_cross_offdiag_.data() + 4 * static_cast<std::size_t>(inc.offsets[i + 1]), 0.0);
    }
    for (int k = inc.offsets[i]; k < inc.offsets[i + 1]; ++k) {
      const int e = inc.edge[k];
      const int j = inc.neighbour[k];
      const Vec2 n_e = dual_.edge_normal[e];
      const double vn_out =
          inc.sign[k] * 0.5 * ((w_[i][1] + w_[j][1]) * n_e.x + (w_[i][2] + w_[j][2]) * n_e.y);
      const double inflow = std::max(-vn_out, 0.0);
      const double c = norm(n_e) / norm(dual_.coords[j] - dual_.coords[i]);
      const double d_face = 0.5 * (diffusivity[i] + diffusivity[j]);
      const double k_i = c / sa::sigma * ((1.0 + sa::cb2) * d_face - sa::cb2 * diffusivity[i]);
      const double jump = nu_tilde_[j] - nu_tilde_[i];
      r += (inflow + k_i) * jump;
      if (cross && inflow > 0.0) {
        // d(-inflow jump)/dU through the face velocity (u_i + u_j)/2, u = (rho u)/rho
        const double g = jump * inc.sign[k] * 0.5;
        double* di = sa_cross_diag_.data() + 4 * static_cast<std::size_t>(i);
        double* dj = sa_cross_offdiag_.data() + 4 * static_cast<std::size_t>(k);
        const double ri = g / w_[i][0], rj = g / w_[j][0];
        di[0] -= ri * (w_[i][1] * n_e.x + w_[i][2] * n_e.y);
        di[1] += ri * n_e.x;
        di[2] += ri * n_e.y;
        dj[0] -= rj * (w_[j][1] * n_e.x + w_[j][2] * n_e.y);
        dj[1] += rj * n_e.x;
        dj[2] += rj * n_e.y;
      }
      if (jacobian && exact) {
        // the whole derivative, with that of the diffusivities D(nu_tilde) at i and j
        const double dk_dj = c / sa::sigma * (1.0 + sa::cb2) * 0.5 * diffusivity_slope[j];
        const double dk_di =
            c / sa::sigma * ((1.0 + sa::cb2) * 0.5 - sa::cb2) * diffusivity_slope[i];
        d += inflow + k_i - dk_di * jump;
        sa_offdiag_[k] = -(inflow + k_i + dk_dj * jump);
      } else if (jacobian) {
        const double a = inflow + std::max(k_i, 0.0);
        d += a;
        sa_offdiag_[k] = -a;
      }
    }
    sa_res_[i] = -r;
    if (jacobian)
      sa_diag_[i] = d;
  }
  for (const auto& face : dual_.boundary_faces) {
    const int i = face.node;
    State outside;
    const double vn = turbulence_inflow(face, outside);
    if (vn >= 0.0)
      continue;
    const double nu_b = visc.viscosity(gas_.temperature(outside)) / outside[0];
    sa_res_[i] -= -vn * (settings_.sa_freestream_ratio * nu_b - nu_tilde_[i]);
    if (jacobian)
      sa_diag_[i] += -vn;
  }
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    if (wall_node_bc_[i] >= 0) {
      // strong nu_tilde = 0 on no-slip walls
      sa_res_[i] = nu_tilde_[i];
      if (jacobian) {
        sa_diag_[i] = 1.0;
        for (int k = inc.offsets[i]; k < inc.offsets[i + 1]; ++k)
          sa_offdiag_[k] = 0.0;
      }
      if (cross) {
        std::fill_n(sa_cross_diag_.data() + 4 * static_cast<std::size_t>(i), 4, 0.0);
        std::fill(sa_cross_offdiag_.data() + 4 * static_cast<std::size_t>(inc.offsets[i]),
                  sa_cross_offdiag_.data() + 4 * static_cast<std::size_t>(inc.offsets[i + 1]), 0.0);
      }
      continue;
    }
    const double volume = dual_.volume[i];
    const double vorticity = std::abs(grad_[i][4] - grad_[i][3]);  // |dv/dx - du/dy|
    const sa::Source src =
        sa::source(nu_tilde_[i], nu[i], vorticity, wall_distance_[i], settings_.sa_ft2);
    sa_res_[i] -= volume * (src.production - src.destruction);
    const double omega_signed = grad_[i][4] - grad_[i][3];
    if (cross && omega_signed != 0.0) {
      // through the vorticity of the least-squares gradient, grad_i = sum_k c_k (q_j - q_i):
      // d Omega_i / d u_j = -sign c_k,y, d Omega_i / d v_j = sign c_k,x
      const double g = -volume *
                       sa::source_vorticity_derivative(nu_tilde_[i], nu[i], vorticity,
                                                       wall_distance_[i], settings_.sa_ft2) *
                       (omega_signed > 0.0 ? 1.0 : -1.0);
      double* di = sa_cross_diag_.data() + 4 * static_cast<std::size_t>(i);
      for (int k = inc.offsets[i]; k < inc.offsets[i + 1]; ++k) {
        const int j = inc.neighbour[k];
        const Vec2 c = lsq_.coefficient[k];
        const double a_u = -g * c.y, a_v = g * c.x;  // d sa_res_i / d u_j, d v_j
        double* dj = sa_cross_offdiag_.data() + 4 * static_cast<std::size_t>(k);
        dj[0] -= (a_u * w_[j][1] + a_v * w_[j][2]) / w_[j][0];
        dj[1] += a_u / w_[j][0];
        dj[2] += a_v / w_[j][0];
        di[0] += (a_u * w_[i][1] + a_v * w_[i][2]) / w_[i][0];
        di[1] -= a_u / w_[i][0];
        di[2] -= a_v / w_[i][0];
      }
    }
    if (jacobian) {
      sa_diag_[i] -= volume * (exact ? src.d_source_exact : src.d_source);
    }
    if (time_dt_ > 0.0) {
      // physical time derivative (see begin_time_step)
      double dnu = time_a_[0] * nu_tilde_[i] - time_a_[1] * time_nu_n_[i];
      if (time_a_[2] != 0.0)
        dnu += time_a_[2] * time_nu_nm1_[i];
      sa_res_[i] += volume * dnu / time_dt_;
      if (jacobian)
        sa_diag_[i] += physical_time_diagonal(i);
    }
  }
}

double FlowSolver::turbulence_inflow(const BoundaryFace& face, State& outside) const {
  const int i = face.node;
  const BoundaryCondition& bc = bcs_[face.curve];
  const double vn = w_[i][1] * face.normal.x + w_[i][2] * face.normal.y;
  if (vn >= 0.0 || bc.kind == BcKind::slip_wall || bc.kind == BcKind::symmetry || bc.no_slip())
    return 0.0;
  outside = w_[i];
  if (bc.kind == BcKind::farfield)
    outside = bc.node_freestream.empty() ? bc.freestream : bc.node_freestream[i];
  return vn;
}

double FlowSolver::turbulence_residual_norm() const {
  double sum2 = 0.0;
  for (int i = 0; i < dual_.num_nodes; ++i) {
    if (wall_node_bc_[i] >= 0)
      continue;
    const double r = sa_res_[i] / dual_.volume[i];
    sum2 += r * r;
  }
  return std::sqrt(sum2 / dual_.num_nodes);
}

double FlowSolver::turbulence_step(double cfl) {
  // One implicit step of the nu_tilde equation with the local time step of the mean flow,
  // solved by three ILU(0)-preconditioned defect corrections.
  const int n = dual_.num_nodes;
  std::vector<double> time_term(n);
  for (int i = 0; i < n; ++i)
    time_term[i] = spectral_radius_[i] / cfl;
  turbulence_residual(true, &time_term);
  const double rms = turbulence_residual_norm();
  std::vector<double> rhs(n), delta;
  for (int i = 0; i < n; ++i)
    rhs[i] = -sa_res_[i];
  solve_scalar(dual_.node_edges, sa_diag_, sa_offdiag_, rhs, delta, 3, sa_ilu_);
  // The same physicality-based step limit as the coupled update: nu_tilde may change by at
  // most max_turbulence_update of its scale |nu_tilde| + nu per step. (nasa-2dcd NPR 5.423 at
  // second order: one unlimited step made nu_tilde's residual jump from 11 to 7e8 at the
  // model's outer wall, where the entrained flow is nearly at rest, and the run diverged.)
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(delta[i]))
      continue;
    const double limit = settings_.max_turbulence_update * (std::abs(nu_tilde_[i]) + sa_nu_[i]);
    nu_tilde_[i] += std::clamp(delta[i], -limit, limit);
  }
  return rms;
}

int rises_at_ceiling(int count, double residual, double previous, double cfl, double ceiling) {
  return cfl >= 0.5 * ceiling && residual > previous ? count + 1 : 0;
}

SolverSettings first_order_start_settings(const SolverSettings& second, double drop) {
  SolverSettings first = second;
  first.order = 1;
  first.residual_drop = std::max(second.residual_drop, drop);
  first.residual_drop_at_cfl_ceiling = true;
  first.cfl_max = std::min(second.cfl_max, SolverSettings{}.cfl_max);
  if (second.turbulence_coupling == TurbulenceCoupling::automatic)
    first.turbulence_coupling = TurbulenceCoupling::segregated;
  return first;
}

void FlowSolver::set_uniform(const State& w) {
  set_primitive(std::vector<State>(dual_.num_nodes, w));
}

void FlowSolver::set_primitive(const std::vector<State>& w) {
  if (static_cast<int>(w.size()) != dual_.num_nodes)
    throw std::invalid_argument("flow: state size differs from mesh");
  for (int i = 0; i < dual_.num_nodes; ++i)
    u_[new_of_old_[i]] = gas_.conservative(w[i]);
  apply_strong_conditions(u_);
  limiter_frozen_ = false;
  limiter_stale_ = true;
  // a restart overrides these with set_nu_tilde() or set_sst()
  if (sst())
    set_freestream_sst();
  else
    set_freestream_nu_tilde();
}

std::vector<State> FlowSolver::primitive() const {
  std::vector<State> w(u_.size());
  for (std::size_t i = 0; i < u_.size(); ++i)
    w[i] = gas_.primitive(u_[new_of_old_[i]]);
  return w;
}

std::vector<State> FlowSolver::conservative() const {
  std::vector<State> u(u_.size());
  for (std::size_t i = 0; i < u_.size(); ++i)
    u[i] = u_[new_of_old_[i]];
  return u;
}

std::vector<double> FlowSolver::node_area() const {
  std::vector<double> a(u_.size());
  for (std::size_t i = 0; i < u_.size(); ++i)
    a[i] = dual_.area[new_of_old_[i]];
  return a;
}

void FlowSolver::apply_strong_conditions(std::vector<State>& u) const {
  for (int i = 0; i < dual_.num_nodes; ++i) {
    if (fixed_node_[i])
      u[i] = fixed_u_[i];
    const int b = wall_node_bc_[i];
    if (b < 0)
      continue;
    const double rho = u[i][0];
    const double p_internal =
        (gas_.gamma - 1.0) * (u[i][3] - 0.5 * (u[i][1] * u[i][1] + u[i][2] * u[i][2]) / rho);
    u[i][1] = 0.0;
    u[i][2] = 0.0;
    u[i][3] = bcs_[b].kind == BcKind::wall_isothermal ? rho * gas_.cv() * wall_temperature_at(b, i)
                                                      : p_internal / (gas_.gamma - 1.0);
  }
}

bool FlowSolver::physical(const std::vector<State>& u) const {
  for (const auto& s : u) {
    const double rho = s[0];
    const double p = (gas_.gamma - 1.0) * (s[3] - 0.5 * (s[1] * s[1] + s[2] * s[2]) / rho);
    // p must stand clear of the round-off of rho E - rho |V|^2 / 2: a near-vacuum node whose
    // pressure is cancellation noise is positive by one formula and negative by another
    if (!(rho > 0.0) || !(p > kPressureFloor * s[3]) || !std::isfinite(p))
      return false;
  }
  return true;
}

void FlowSolver::compute_residual(bool update_limiter) {
  const auto started = std::chrono::steady_clock::now();
  evaluate_residual(update_limiter);
  ++residual_evaluations_;
  residual_seconds_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

void FlowSolver::evaluate_residual(bool update_limiter) {
  const int n = dual_.num_nodes;
  const int ne = dual_.num_edges();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i)
    w_[i] = gas_.primitive(u_[i]);

  const bool second = settings_.order >= 2;
  const bool axi = dual_.geometry == Geometry::axisymmetric;
  const bool turbulent = settings_.turbulent;
  if ((second && !recon_mapped_) || settings_.viscous)
    lsq_gradients(dual_, lsq_, w_, grad_);
  update_eddy_viscosity();  // after the gradients: SST's mu_t needs the strain rate
  if (second && recon_mapped_)
    lsq_gradients(dual_, recon_lsq_, w_, recon_grad_);
  const auto& rgrad = recon_mapped_ ? recon_grad_ : grad_;
  if (second && settings_.limiter && update_limiter) {
    if (settings_.venkat_wang > 0.0)
      venkat_eps_ = make_wang_epsilon(w_, settings_.venkat_wang, n);
    venkatakrishnan_limiter(dual_, recon_stencil_.to_neighbour, w_, rgrad, venkat_eps_, phi_);
    limiter_stale_ = false;
  }
  const bool limit = settings_.limiter;

#pragma omp parallel for schedule(static)
  for (int e = 0; e < ne; ++e) {
    const int i = dual_.edges[e][0];
    const int j = dual_.edges[e][1];
    const Vec2 n_e = dual_.edge_normal[e];
    State wl = w_[i];
    State wr = w_[j];
    if (second) {
      // reconstruction to the edge midpoint, each side along its own stencil vector (Cartesian,
      // or wall-aligned in stretched wall layers)
      wl = reconstruct(w_[i], rgrad[i], limit ? &phi_[i] : nullptr, recon_half_ij_[e]);
      wr = reconstruct(w_[j], rgrad[j], limit ? &phi_[j] : nullptr, recon_half_ji_[e]);
    }
    State f = roe_flux(gas_, wl, wr, n_e.x, n_e.y, settings_.entropy_fix);
    if (settings_.viscous) {
      const State fv =
          viscous_flux(gas_, settings_.viscosity, dual_.coords[i], dual_.coords[j], w_[i], w_[j],
                       grad_[i], grad_[j], axi ? n_e : dual_.edge_normal_planar[e],
                       axi ? norm(n_e) / norm(dual_.edge_normal_planar[e]) : 0.0, nullptr,
                       turbulent ? 0.5 * (eddy_viscosity_[i] + eddy_viscosity_[j]) : 0.0);
      for (int v = 0; v < 4; ++v)
        f[v] -= fv[v];
    }
    edge_flux_[e] = f;
  }

  const auto& inc = dual_.node_edges;
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    State r{};
    double lambda = 0.0;
    const double ci = gas_.sound_speed(w_[i]);
    // viscous spectral radius coefficient of node i (Blazek 2015, eq. 6.22), once per node
    const double viscous_coefficient =
        settings_.viscous
            ? std::max(4.0 / 3.0, gas_.gamma / settings_.viscosity.prandtl) *
                  (settings_.viscosity.viscosity(gas_.temperature(w_[i])) + eddy_viscosity_[i]) /
                  w_[i][0] / dual_.area[i]
            : 0.0;
    for (int k = inc.offsets[i]; k < inc.offsets[i + 1]; ++k) {
      const int e = inc.edge[k];
      const double s = inc.sign[k];
      for (int v = 0; v < 4; ++v)
        r[v] += s * edge_flux_[e][v];
      const int j = inc.neighbour[k];
      const Vec2 n_e = dual_.edge_normal[e];
      const double vn = 0.5 * ((w_[i][1] + w_[j][1]) * n_e.x + (w_[i][2] + w_[j][2]) * n_e.y);
      const double c = 0.5 * (ci + gas_.sound_speed(w_[j]));
      lambda += std::abs(vn) + c * norm(n_e);  // Blazek 2015, eq. 6.21
      if (settings_.viscous) {
        // viscous spectral radius (Blazek 2015, eq. 6.22). Axisymmetric: this planar term sits
        // next to the r-weighted convective one, so it is 1/r too large there (units m^2/s
        // against m^3/s per radian). Scaling it by volume/area (consistent units) left the
        // steady solutions unchanged but slowed convergence: turbulent pipe 989 instead of 402
        // iterations, Poiseuille 375 instead of 290, BMG SA 71x41 193 instead of 131; kept.
        const double sn = norm(dual_.edge_normal_planar[e]);
        lambda += viscous_coefficient * sn * sn;
      }
    }
    res_[i] = r;
    spectral_radius_[i] = lambda;
  }

  // The boundary faces' fluxes, threaded, then added to their nodes in face order (a node has
  // two faces: the sum stays serial and in the same order). Serial, the fluxes were 0.5 % of a
  // two-thread run on nasa-2dcd's case mesh, with the second thread idle.
  const int num_faces = static_cast<int>(dual_.boundary_faces.size());
  face_flux_.resize(num_faces);
  face_spectral_radius_.resize(num_faces);
#pragma omp parallel for schedule(static)
  for (int face_index = 0; face_index < num_faces; ++face_index) {
    const auto& face = dual_.boundary_faces[face_index];
    const State& w = w_[face.node];
    State wf = w;
    if (second) {
      // State at the middle of the half edge: makes the boundary flux integral exact for linear
      // variations (e.g. the wall pressure on a curved wall), keeping the scheme second order.
      wf = reconstruct(w, rgrad[face.node], limit ? &phi_[face.node] : nullptr,
                       recon_stencil_.to_face[face_index]);
    }
    face_flux_[face_index] =
        boundary_flux(gas_, bcs_[face.curve], wf, face.normal, face.node, settings_.entropy_fix);
    const double vn = w[1] * face.normal.x + w[2] * face.normal.y;
    face_spectral_radius_[face_index] = std::abs(vn) + gas_.sound_speed(w) * norm(face.normal);
  }
  for (int face_index = 0; face_index < num_faces; ++face_index) {
    const int i = dual_.boundary_faces[face_index].node;
    for (int v = 0; v < 4; ++v)
      res_[i][v] += face_flux_[face_index][v];
    spectral_radius_[i] += face_spectral_radius_[face_index];
  }

  if (dual_.geometry == Geometry::axisymmetric) {
    // source of the radial momentum equation, integral of (p - tau_theta_theta) dA over the
    // dual cell (White 2006, eq. 2-29 in cylindrical coordinates)
    for (int i = 0; i < n; ++i) {
      double source = w_[i][3];
      if (settings_.viscous) {
        source -= hoop_stress(gas_, settings_.viscosity, w_[i], grad_[i], dual_.coords[i].y,
                              eddy_viscosity_[i]);
      }
      res_[i][2] -= source * dual_.area[i];
    }
  }
  add_physical_time_derivative();
  if (turbulent && turbulence_coupled_)
    turbulence_residual(false, nullptr);
}

void FlowSolver::begin_time_step(double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt))
    throw std::invalid_argument("flow: physical time step must be positive");
  const bool first = time_u_n_.empty() || dt != time_dt_;
  time_u_nm1_ = std::move(time_u_n_);
  time_u_n_ = u_;
  time_nu_nm1_ = std::move(time_nu_n_);
  time_nu_n_ = turbulence_snapshot();  // SA: nu_tilde; SST: k then omega
  time_dt_ = dt;
  // BDF1 on the first step (and after a change of dt), BDF2 after it
  time_a_ = first ? std::array<double, 3>{1.0, 1.0, 0.0} : std::array<double, 3>{1.5, 2.0, 0.5};
}

void FlowSolver::hold_limiter_at_predicted_state() {
  hold_limiter(false);
  limiter_stale_ = true;  // evaluated at U^n by the next solve() unless U* below is physical
  // (a first-order backward difference, the first step or one after a change of dt, has no
  // level U^(n-1) one dt back to extrapolate from)
  if (time_u_nm1_.empty() || time_a_[2] == 0.0 || settings_.order < 2 || !settings_.limiter)
    return;
  std::vector<State> predicted(u_.size());
  for (std::size_t i = 0; i < u_.size(); ++i) {
    for (int v = 0; v < 4; ++v)
      predicted[i][v] = 2.0 * time_u_n_[i][v] - time_u_nm1_[i][v];
  }
  apply_strong_conditions(predicted);
  if (!physical(predicted))
    return;
  std::vector<State> start = std::move(u_);
  u_ = std::move(predicted);
  compute_residual(true);
  u_ = std::move(start);
  limiter_stale_ = false;  // the next solve() evaluates everything at U^n but the limiter
}

void FlowSolver::set_inner_iteration_control(int max_iterations, double residual_drop,
                                             double cfl_start, int print_every) {
  settings_.max_iterations = max_iterations;
  settings_.residual_drop = residual_drop;
  settings_.residual_reference = 0.0;
  settings_.stationary_tolerance = 0.0;
  settings_.inflow_ramp_iterations = 0;
  settings_.cfl_start = cfl_start;
  settings_.print_every = print_every;
}

void FlowSolver::add_physical_time_derivative() {
  if (time_dt_ <= 0.0)
    return;
  const int n = dual_.num_nodes;
  const auto [a0, a1, a2] = time_a_;
  const bool bdf2 = a2 != 0.0;
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const double v_dt = dual_.volume[i] / time_dt_;
    for (int v = 0; v < 4; ++v) {
      double du = a0 * u_[i][v] - a1 * time_u_n_[i][v];
      if (bdf2)
        du += a2 * time_u_nm1_[i][v];
      res_[i][v] += v_dt * du;
    }
  }
}

std::vector<double> FlowSolver::jacobian_product(const std::vector<double>& x, bool assembled) {
  const ScopedThreads threads(settings_.threads);
  const bool coupled_before = turbulence_coupled_;
  turbulence_coupled_ = settings_.turbulent;
  if (turbulence_coupled_ && jac_coupled_.num_rows == 0)
    jac_coupled_ = make_pattern(dual_.num_nodes, dual_.edges, 5);
  const std::vector<double> no_time_term(dual_.num_nodes, 0.0);
  compute_residual(true);
  assemble_jacobian(no_time_term);
  if (turbulence_coupled_) {
    turbulence_residual(true, &no_time_term);
    assemble_coupled_jacobian();
  }
  const int nb = turbulence_coupled_ ? 5 : 4;
  if (x.size() != nb * static_cast<std::size_t>(dual_.num_nodes))
    throw std::invalid_argument("flow: jacobian_product needs 4 (5 with SA) values per node");
  std::vector<double> x_internal(x.size()), y_internal(x.size()), y(x.size());
  for (int i = 0; i < dual_.num_nodes; ++i) {
    for (int v = 0; v < nb; ++v)
      x_internal[nb * static_cast<std::size_t>(new_of_old_[i]) + v] =
          x[nb * static_cast<std::size_t>(i) + v];
  }
  if (assembled)
    system_matrix().multiply(x_internal, y_internal);
  else
    matrix_free_operator(no_time_term)(x_internal, y_internal);
  for (int i = 0; i < dual_.num_nodes; ++i) {
    for (int v = 0; v < nb; ++v)
      y[nb * static_cast<std::size_t>(i) + v] =
          y_internal[nb * static_cast<std::size_t>(new_of_old_[i]) + v];
  }
  compute_residual(false);
  turbulence_coupled_ = coupled_before;
  return y;
}

std::vector<State> FlowSolver::residual() {
  const ScopedThreads threads(settings_.threads);
  compute_residual(true);
  std::vector<State> r(res_.size());
  for (std::size_t i = 0; i < r.size(); ++i)
    r[i] = res_[new_of_old_[i]];
  return r;
}

bool FlowSolver::residual_row_counted(int i, int v) const {
  if (fixed_node_[i])
    return false;
  const int b = wall_node_bc_[i];
  if (b < 0)
    return true;
  // imposed at walls: the momentum, and an isothermal wall's energy
  return !((v > 0 && v < 3) || (v == 3 && bcs_[b].kind == BcKind::wall_isothermal));
}

State FlowSolver::residual_norm() const {
  State s{};
  for (int i = 0; i < dual_.num_nodes; ++i) {
    for (int v = 0; v < 4; ++v) {
      if (!residual_row_counted(i, v))
        continue;
      const double r = res_[i][v] / dual_.volume[i];
      s[v] += r * r;
    }
  }
  for (int v = 0; v < 4; ++v)
    s[v] = std::sqrt(s[v] / dual_.num_nodes);
  return s;
}

bool FlowSolver::exact_roe_jacobian_by_settings() const {
  return settings_.roe_jacobian == RoeJacobian::exact ||
         (settings_.roe_jacobian == RoeJacobian::exact_first_order && settings_.order == 1);
}

LinearOperator FlowSolver::matrix_free_operator(const std::vector<double>& diag_scale) {
  // Rows the assembled Jacobian replaces (strong wall conditions, imposed far-field nodes) keep
  // their assembled form; every other row is V/dt x + (R(u + eps x) - R(u)) / eps with the
  // limiter frozen at its current value, so the product is the derivative of the residual the
  // iteration drives to zero. Coupled: nu_tilde is the fifth unknown of each node and its row
  // the nu_tilde residual times sa_row_scale_.
  const int n = dual_.num_nodes;
  const bool coupled = turbulence_coupled_;
  const int nb = coupled ? 5 : 4;
  // The base state and residuals, copied into buffers kept from one Newton step to the next
  // and threaded: fresh copies per step were 0.3 % of a two-thread run on nasa-2dcd's case mesh,
  // page faults included, with the second thread idle.
  MatrixFreeBase* base = &matrix_free_base_;
  base->u.resize(n);
  base->res.resize(n);
  base->nu.resize(coupled ? n : 0);
  base->sa_res.resize(coupled ? n : 0);
  base->nu_scale.resize(coupled ? n : 0);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    base->u[i] = u_[i];
    base->res[i] = res_[i];
    if (coupled) {
      base->nu[i] = nu_tilde_[i];
      base->sa_res[i] = sa_res_[i];
    }
  }
  double u_norm2 = 0.0;
  for (const auto& s : u_) {
    for (double c : s)
      u_norm2 += c * c;
  }
  const double u_norm = std::sqrt(u_norm2);
  // nu_tilde's own scale per node (|nu_tilde| + nu, nu_tilde may be 0 or negative) and the
  // weight that makes the perturbation of nu_tilde as relative as that of the mean flow
  double nu_weight = 0.0;
  if (coupled) {
    double nu_norm2 = 0.0;
    for (int i = 0; i < n; ++i) {
      const double s = std::abs(nu_tilde_[i]) + sa_nu_[i];
      base->nu_scale[i] = s;
      nu_norm2 += s * s;
    }
    nu_weight = u_norm / std::max(std::sqrt(nu_norm2), 1e-300);
  }
  return [this, n, nb, coupled, base, nu_weight, u_norm, &diag_scale](const std::vector<double>& x,
                                                                      std::vector<double>& y) {
    // the assembled rows are needed only where they replace the residual difference
    y.resize(x.size());
    system_matrix().multiply_rows(x, y, assembled_rows_);
    // The norm of x and the smallest node limit (below) in one threaded pass over fixed chunks,
    // the partial sums added in chunk order: the same bits whatever the thread count. Serial,
    // the norm was 0.4 % of a two-thread run on nasa-2dcd's case mesh, with the second thread
    // idle.
    //
    // The perturbation eps is relative, ~1e-7: half the digits for the difference, half for its
    // accuracy (Knoll and Keyes 2004, eq. 11, with the state norm as the scale), but small
    // enough that no node's density or pressure changes by more than 1e-6 of its value: a
    // near-vacuum node (a lip corner) perturbed by the global scale leaves the linear range and
    // its difference quotient stalled GMRES once the residual was small. Not below 1e-4 of the
    // global choice, where round-off would take over.
    double chunk_norm2[kReductionChunks];
    double chunk_limit[kReductionChunks];
#pragma omp parallel for schedule(static)
    for (int c = 0; c < kReductionChunks; ++c) {
      double norm2 = 0.0;
      double limit = std::numeric_limits<double>::infinity();
      const int last = static_cast<int>(chunk_begin(n, c + 1));
      for (int i = static_cast<int>(chunk_begin(n, c)); i < last; ++i) {
        const State& u = base->u[i];
        const double* xi = x.data() + nb * static_cast<std::size_t>(i);
        norm2 += xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2] + xi[3] * xi[3];
        if (coupled)
          norm2 += nu_weight * nu_weight * xi[4] * xi[4];
        const double rho = u[0];
        const double vx = u[1] / rho, vy = u[2] / rho;
        const double p = (gas_.gamma - 1.0) * (u[3] - 0.5 * rho * (vx * vx + vy * vy));
        const double dp = (gas_.gamma - 1.0) *
                          (xi[3] - vx * xi[1] - vy * xi[2] + 0.5 * (vx * vx + vy * vy) * xi[0]);
        if (xi[0] != 0.0)
          limit = std::min(limit, 1e-6 * rho / std::abs(xi[0]));
        if (dp != 0.0)
          limit = std::min(limit, 1e-6 * p / std::abs(dp));
        if (coupled && xi[4] != 0.0)
          limit = std::min(limit, 1e-6 * base->nu_scale[i] / std::abs(xi[4]));
      }
      chunk_norm2[c] = norm2;
      chunk_limit[c] = limit;
    }
    double x_norm2 = 0.0;
    double node_limit = std::numeric_limits<double>::infinity();
    for (int c = 0; c < kReductionChunks; ++c) {
      x_norm2 += chunk_norm2[c];
      node_limit = std::min(node_limit, chunk_limit[c]);
    }
    const double x_norm = std::sqrt(x_norm2);
    if (x_norm == 0.0) {
      system_matrix().multiply(x, y);
      return;
    }
    double eps = 1e-7 * std::max(u_norm, 1.0) / x_norm;
    eps = std::max(std::min(eps, node_limit), 1e-4 * eps);
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i) {
      for (int v = 0; v < 4; ++v)
        u_[i][v] = base->u[i][v] + eps * x[nb * i + v];
      if (coupled)
        nu_tilde_[i] = base->nu[i] + eps * x[nb * i + 4];
    }
    compute_residual(false);
    // the base state is restored in this threaded loop (a serial copy was 1 % of a two-thread
    // run on nasa-2dcd's case mesh)
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i) {
      u_[i] = base->u[i];
      if (coupled)
        nu_tilde_[i] = base->nu[i];
      const bool wall = wall_node_bc_[i] >= 0;
      if (coupled && !wall) {
        y[nb * i + 4] =
            sa_row_scale_ * (diag_scale[i] * x[nb * i + 4] + (sa_res_[i] - base->sa_res[i]) / eps);
      }
      if (fixed_node_[i])
        continue;
      const bool iso = wall && bcs_[wall_node_bc_[i]].kind == BcKind::wall_isothermal;
      for (int v = 0; v < 4; ++v) {
        if (wall && (v == 1 || v == 2 || (v == 3 && iso)))
          continue;
        y[nb * i + v] = diag_scale[i] * x[nb * i + v] + (res_[i][v] - base->res[i][v]) / eps;
      }
    }
  };
}

// The running variables of solve()'s pseudo-time loop, shared by its phases so that each phase
// is a function of the loop state rather than of 40 locals: the report being built, the step's
// work vectors, the CFL control, the Newton phase, the best state and the stationarity test.
// One per solve() call; nothing of it outlives the call but the report.
struct FlowSolver::SolveLoop {
  std::chrono::steady_clock::time_point start;
  SolveReport report;
  long evaluations_before = 0;
  double residual_seconds_before = 0.0;
  int n = 0;             // nodes
  bool coupled = false;  // coupled SA Newton steps (turbulence_coupled_)
  int nb = 4;            // unknowns per node
  std::vector<double> rhs, du;
  std::vector<double> diag_scale;  // V / dt per node
  // the state before the last update, for a return after a non-physical one
  std::vector<State> u_good;
  std::vector<double> nu_good;
  // the residual the last step was taken from, with the limiter and coupling it was taken with
  // (infinite: no step since the last check; see take_back_jumped_step)
  double stepped_from = std::numeric_limits<double>::infinity();
  bool stepped_limiter_frozen = false;
  bool stepped_coupled = false;
  bool stepped_newton = false;  // ... and whether it was a Newton-Krylov step
  double cfl = 0.0;
  double cfl_scale = 1.0;
  double last_omega = 1.0;
  bool last_linear_failed = false;  // the last GMRES solve left more than half its residual
  // the last assembled (defect-correction or first-order) GMRES solve stopped above its
  // tolerance, at its iteration limit
  bool last_linear_short = false;
  int collapsed = 0;
  double r_previous = std::numeric_limits<double>::infinity();
  double r_max = 0.0;
  double r_min = std::numeric_limits<double>::infinity();
  int last_minimum = 0;
  double cfl_ceiling = 0.0;
  int last_progress = 0;  // last new minimum or last ceiling cut
  int newton_fallbacks = 0;  // Newton phases abandoned (see abandon_failed_newton_phase())
  int newton_from = 0;  // first Newton-Krylov iteration of an after_limiter_freeze run
  // the state, residual and CFL number where the Newton phase began (its last good state)
  std::vector<State> newton_start_u;
  std::vector<double> newton_start_nu;
  double newton_start_residual = 0.0, newton_start_cfl = 0.0;
  // Eisenstat-Walker forcing: the previous Newton step's density residual and tolerance
  double newton_residual_previous = 0.0;
  double forcing_previous = 0.0;
  std::vector<double> residual_by_iteration;  // density residual per iteration of this solve
  int last_slow_cut = 0;
  int rises_at_ceiling = 0;  // iterations in a row whose density residual rose, at the ceiling
  // the state at the lowest density residual so far and its iteration, for a diverged march
  std::vector<State> best_u;
  std::vector<double> best_nu;
  int best_iteration = 0;
  DivergedMarch diverged_march;
  bool release_if_far = false;  // a held limiter, let go at the first iteration if far off
  std::vector<double> target_total_pressure;  // per boundary condition, the ramp's end value
  int ramp = 0;                               // inflow ramp iterations
  // the ramp's rises so far (ramp_rises / ramp of the way), the iteration it reached the full
  // pressure (before that: a number past any iteration), and whether it holds this iteration
  int ramp_rises = 0;
  int ramp_end = 0;
  bool ramp_held = false;
  // wall nodes and faces for the stationarity criterion, and their last iteration's values
  std::vector<int> wall_nodes;
  std::vector<const BoundaryFace*> wall_faces;
  std::vector<double> wall_p_previous;
  Vec2 wall_force_previous{};
  int stationary_count = 0;
  // The current iteration: its number, residual norm, record, linear solve, and the relaxation
  // of its update (smallest omega, where, and at how many nodes the update was relaxed).
  int it = 0;
  State rnorm{};
  IterationRecord rec;
  GmresResult lin;
  double omega_min = 1.0;
  int omega_node = -1;
  int limited = 0;
};

// The pseudo-time march: each iteration evaluates the residual of the current state, lets the
// safeguards act on it (returns to an earlier state, CFL ceiling, limiter freezing), sets the
// CFL number, tests convergence, and takes one implicit step. Each phase is a member function
// below, in the order they run.
SolveReport FlowSolver::solve() {
  const ScopedThreads threads(settings_.threads);
  SolveLoop s;
  start_run(s);
  for (s.it = 1; s.it <= settings_.max_iterations; ++s.it) {
    switch_turbulence_coupling(s);
    ramp_inflow(s);
    compute_residual(!limiter_frozen_);
    s.rnorm = residual_norm();
    shorten_rising_step(s);
    if (!std::isfinite(s.rnorm[0] + s.rnorm[1] + s.rnorm[2] + s.rnorm[3])) {
      back_off_to_good_state(s);
      if (s.report.backoffs > 20)
        break;
      continue;
    }
    release_held_limiter_if_far(s);
    if (take_back_jumped_step(s))
      continue;
    if (track_residual(s))
      continue;  // diverged: back to the best state
    cut_cfl_ceiling_on_stall(s);
    freeze_limiter(s);
    if (abandon_failed_newton_phase(s))
      continue;
    update_cfl(s);
    begin_record(s);
    if (check_convergence(s))
      break;
    linear_step(s);
    relax_update(s);
    if (segregated_turbulence_step(s))
      s.rec.turbulence_residual = sst() ? sst_step(s.cfl) : turbulence_step(s.cfl);
    accept_or_reject_step(s);
    s.stepped_from = s.rnorm[0];
    s.stepped_limiter_frozen = limiter_frozen_;
    s.stepped_coupled = s.coupled;
    s.stepped_newton = newton_krylov_step(s);
    report_progress(s);
    if (march_stopped(s))
      break;
  }
  finish_run(s);
  return std::move(s.report);
}

// Everything the loop needs before its first iteration: the counters the report takes
// differences of, the step's vectors, the CFL control's start values, the limiter held by
// hold_limiter(), the inflow ramp's targets and the walls of the stationarity criterion.
void FlowSolver::start_run(SolveLoop& s) {
  s.start = std::chrono::steady_clock::now();
  s.evaluations_before = residual_evaluations_;
  s.residual_seconds_before = residual_seconds_;
  s.n = dual_.num_nodes;
  const int n = s.n;
  turbulence_coupled_ =
      settings_.turbulent && settings_.turbulence_coupling == TurbulenceCoupling::coupled;
  s.coupled = turbulence_coupled_;
  s.nb = s.coupled ? 5 : 4;
  s.rhs.resize(s.nb * static_cast<std::size_t>(n));
  s.du.resize(s.nb * static_cast<std::size_t>(n));
  s.diag_scale.resize(n);
  s.u_good = u_;
  s.nu_good = turbulence_snapshot();
  s.cfl = settings_.cfl_start;
  s.r_max = settings_.residual_reference;
  s.cfl_ceiling = settings_.cfl_max;
  s.forcing_previous = settings_.matrix_free_linear_tolerance;
  exact_roe_jacobian_ = exact_roe_jacobian_by_settings();
  if (hold_limiter_ && limiter_stale_)
    compute_residual(true);  // the limiter of the state set since the last solve, to hold
  limiter_frozen_ = hold_limiter_;
  s.release_if_far = hold_limiter_ && release_held_limiter_;
  hold_limiter_ = release_held_limiter_ = false;
  s.target_total_pressure.resize(bcs_.size());
  for (std::size_t b = 0; b < bcs_.size(); ++b)
    s.target_total_pressure[b] = bcs_[b].total_pressure;
  s.ramp = settings_.inflow_ramp_iterations;
  s.ramp_end = s.ramp > 0 ? std::numeric_limits<int>::max() : 0;
  // wall nodes and faces for the stationarity criterion
  std::vector<char> on_wall(n, 0);
  for (const auto& face : dual_.boundary_faces) {
    const BcKind k = bcs_[face.curve].kind;
    if (k != BcKind::slip_wall && !bcs_[face.curve].no_slip())
      continue;
    s.wall_faces.push_back(&face);
    if (!on_wall[face.node])
      s.wall_nodes.push_back(face.node);
    on_wall[face.node] = 1;
  }
}

// Newton-Krylov steps (the matrix-free second-order operator) this iteration, rather than
// defect correction with the first-order Jacobian; with after_limiter_freeze from the iteration
// on which the limiter is frozen (without a limiter: on which the same criteria are met; Newton
// steps from a cold start did not converge the laminar pipe of PipePoiseuille in 400
// iterations), until kNewtonFallbacks of its phases have failed.
bool FlowSolver::newton_krylov_step(const SolveLoop& s) const {
  return settings_.order >= 2 && (settings_.matrix_free == MatrixFree::on ||
                                  (settings_.matrix_free == MatrixFree::after_limiter_freeze &&
                                   limiter_frozen_ && s.newton_fallbacks < kNewtonFallbacks));
}

bool FlowSolver::segregated_turbulence_step(const SolveLoop& s) const {
  return settings_.turbulent && !s.coupled;
}

// Automatic SA coupling: segregated steps through the start-up transient, coupled Newton steps
// (5 unknowns per node) from the iteration on which the density residual has fallen by
// coupling_switch_drop (see SolverSettings::turbulence_coupling).
void FlowSolver::switch_turbulence_coupling(SolveLoop& s) {
  if (!s.coupled && settings_.turbulence_coupling == TurbulenceCoupling::automatic &&
      s.report.residual_drop <= settings_.coupling_switch_drop && s.it > s.ramp_end) {
    s.coupled = turbulence_coupled_ = true;
    s.nb = 5;
    s.rhs.assign(s.nb * static_cast<std::size_t>(s.n), 0.0);
    s.du.assign(s.nb * static_cast<std::size_t>(s.n), 0.0);
    s.nu_good = turbulence_snapshot();
    s.report.coupled_from = s.it;
    if (settings_.print_every > 0)
      std::fprintf(stderr, "iter %5d  coupled SA Newton steps from here (drop %.2e)\n", s.it,
                   s.report.residual_drop);
  }
}

// The valve opening of a jet started from rest: every stagnation inflow's total pressure at
// this iteration of the ramp (SolverSettings::inflow_ramp_iterations), which rises by 1/ramp of
// the way per iteration unless it holds (SolverSettings::inflow_ramp_hold_mach).
void FlowSolver::ramp_inflow(SolveLoop& s) {
  if (s.ramp <= 0 || s.it > s.ramp_end)
    return;
  const double mach =
      s.it > 1 && settings_.inflow_ramp_hold_mach > 0.0 ? largest_inflow_mach() : 0.0;
  // at most as many iterations held as the ramp has: a duct whose steady inflow Mach number is
  // above the threshold (a straight duct choked at its exit) would otherwise never open
  const bool may_hold = s.report.inflow_ramp_held < s.ramp;
  const bool hold = s.it > 1 && mach > settings_.inflow_ramp_hold_mach && may_hold;
  if (hold != s.ramp_held && settings_.print_every > 0)
    std::fprintf(stderr,
                 hold       ? "iter %5d  inflow ramp held at %.0f %% (inflow Mach %.2f)\n"
                 : may_hold ? "iter %5d  inflow ramp rising from %.0f %% (inflow Mach %.2f)\n"
                            : "iter %5d  inflow ramp rising from %.0f %% (inflow Mach %.2f; "
                              "held as many iterations as the ramp has)\n",
                 s.it, 100.0 * s.ramp_rises / s.ramp, mach);
  s.ramp_held = hold;
  if (hold)
    ++s.report.inflow_ramp_held;
  else
    ++s.ramp_rises;
  if (s.ramp_rises >= s.ramp)
    s.ramp_end = s.report.inflow_ramp_end = s.it;
  const double f = std::min(1.0, static_cast<double>(s.ramp_rises) / s.ramp);
  for (std::size_t b = 0; b < bcs_.size(); ++b) {
    if (bcs_[b].kind != BcKind::stagnation_inflow)
      continue;
    const double p_start =
        std::min(settings_.inflow_ramp_start_pressure, s.target_total_pressure[b]);
    bcs_[b].total_pressure = p_start + f * (s.target_total_pressure[b] - p_start);
  }
}

// The largest Mach number at the nodes of stagnation inflow boundaries.
double FlowSolver::largest_inflow_mach() const {
  double mach = 0.0;
  for (const auto& face : dual_.boundary_faces) {
    if (bcs_[face.curve].kind != BcKind::stagnation_inflow)
      continue;
    const State w = gas_.primitive(u_[face.node]);
    mach = std::max(mach, std::hypot(w[1], w[2]) / gas_.sound_speed(w));
  }
  return mach;
}

// Back to the state before the last step with a tenth of the CFL number: after a non-finite
// residual, or a step the residual jumped after (take_back_jumped_step).
void FlowSolver::back_off_to_good_state(SolveLoop& s) {
  u_ = s.u_good;
  if (s.coupled)
    restore_turbulence(s.nu_good);
  s.cfl_scale *= 0.1;
  s.cfl = std::max(s.cfl * 0.1, 1e-3);
  ++s.report.backoffs;
}

// A restart's held limiter is let go at the first iteration when the state is far from the one
// it was held at (SolverSettings::held_limiter_max_drop).
void FlowSolver::release_held_limiter_if_far(const SolveLoop& s) {
  if (s.it == 1 && s.release_if_far && limiter_frozen_ && s.r_max > 0.0 &&
      s.rnorm[0] > settings_.held_limiter_max_drop * s.r_max) {
    limiter_frozen_ = false;  // a held limiter far from its state (held_limiter_max_drop)
    if (settings_.print_every > 0)
      std::fprintf(stderr,
                   "iter %5d  limiter released: residual drop %.2e at the start is above "
                   "%.2e, too far from the state it was held at\n",
                   s.it, s.rnorm[0] / s.r_max, settings_.held_limiter_max_drop);
  }
}

// This iteration's residual can be compared with the one the last step was taken from (`before`,
// SolveLoop::stepped_from): it comes right after that step, with the limiter (frozen or live)
// and the SA coupling the step was taken with (letting the limiter go or switching the coupling
// changes the residual itself), and not in the inflow ramp, whose boundary values move under it.
bool FlowSolver::right_after_comparable_step(const SolveLoop& s, double before) const {
  return s.it > s.ramp_end && std::isfinite(before) &&
         limiter_frozen_ == s.stepped_limiter_frozen && s.coupled == s.stepped_coupled;
}

bool FlowSolver::right_after_comparable_step(const SolveLoop& s) const {
  return right_after_comparable_step(s, s.stepped_from);
}

// The density row of the pseudo-time residual of the step just taken, V/dt (u - u_before) +
// R(u), per volume and as an RMS over the nodes, as residual_norm() measures R.
double FlowSolver::pseudo_time_residual_norm(const SolveLoop& s) const {
  double sum = 0.0;
  for (int i = 0; i < s.n; ++i) {
    if (fixed_node_[i])
      continue;
    const double g = (s.diag_scale[i] * (u_[i][0] - s.u_good[i][0]) + res_[i][0]) / dual_.volume[i];
    sum += g * g;
  }
  return std::sqrt(sum / s.n);
}

// Line search on the pseudo-time residual (SolverSettings::line_search_halvings): the step just
// taken is halved, and the residual evaluated again, while the density row of V/dt (u -
// u_before) + R(u) stays above line_search_rise times the residual the step was taken from.
// That is the residual the step's linear system linearises: along an exact Newton step of the
// pseudo-time system it falls below R(u_before) for a short enough step, so a rise says the
// linearisation was far off (a defect-correction step whose live limiter switched, a
// node-by-node relaxation that left the field inconsistent) and a shorter step in the same
// direction is the cheaper remedy than a step taken back whole (take_back_jumped_step): one
// residual evaluation per halving, no linear solve. Ceze and Fidkowski's constrained
// pseudo-transient continuation accepts its steps by the same residual. A halved step stays
// physical: density is linear and pressure concave in the conserved variables (segregated SA:
// the mean flow's step only, nu_tilde keeps its own). The CFL number is cut by the fraction of
// the step kept. Only right after a step, with the limiter and SA coupling it was taken with,
// and not in the inflow ramp (as take_back_jumped_step). Not after
// a Newton-Krylov step: there a rising residual is what gives up a Newton phase whose limiter
// froze inside a transient (abandon_failed_newton_phase); halving those steps kept such a phase
// of nasa-2dcd NPR 2.46 going for 30 iterations, and the run converged to that frozen limiter's
// solution (separation x/l_e 0.487 against the live limiter's 0.500).
void FlowSolver::shorten_rising_step(SolveLoop& s) {
  if (settings_.line_search_halvings <= 0 || !right_after_comparable_step(s) || s.stepped_newton ||
      s.u_good.size() != u_.size())
    return;
  const double allowed = settings_.line_search_rise * s.stepped_from;
  const double first = pseudo_time_residual_norm(s);
  double g = first;
  int halvings = 0;
  while (!(g <= allowed) && halvings < settings_.line_search_halvings) {
    ++halvings;
    for (int i = 0; i < s.n; ++i)
      for (int v = 0; v < 4; ++v)
        u_[i][v] = s.u_good[i][v] + 0.5 * (u_[i][v] - s.u_good[i][v]);
    if (s.coupled) {
      std::vector<double> nu = turbulence_snapshot();
      for (std::size_t k = 0; k < nu.size(); ++k)
        nu[k] = s.nu_good[k] + 0.5 * (nu[k] - s.nu_good[k]);
      restore_turbulence(nu);
    }
    compute_residual(!limiter_frozen_);
    s.rnorm = residual_norm();
    g = pseudo_time_residual_norm(s);
  }
  if (halvings == 0)
    return;
  const double kept = std::ldexp(1.0, -halvings);
  s.cfl = std::max(s.cfl * kept, 1e-3);
  ++s.report.steps_shortened;
  s.report.step_halvings += halvings;
  if (settings_.print_every > 0)
    std::fprintf(stderr,
                 "iter %5d  line search: step cut to %g (pseudo-time residual %.2e -> %.2e, "
                 "residual before the step %.2e), CFL %.2e\n",
                 s.it, kept, first, g, s.stepped_from, s.cfl);
}

// A step the residual jumped after is taken back at once: the state before it (relax_update's
// u_good), the CFL number and its scale cut tenfold, counted as a back-off. Only the iteration
// right after a step is compared, and only with the limiter (frozen or live) and the SA coupling
// the step was taken with: a limiter let go or a coupling switched changes the residual itself.
// Node-by-node relaxation keeps each node physical but not the field consistent: on
// Back-Massier-Gier 321 x 81 a coupled Newton step at CFL 320 relaxed to nothing at the exit lip
// was taken, the density residual rose from 2.9e4 to 5.9e7, and the march needed 450 iterations to
// come back (the CFL number dipped below its start value for fewer than DivergedMarch's ten
// iterations, so the return to the best state never came). Taken back, that run converged in 36
// iterations. Not in the inflow ramp, whose boundary values move under the residual, and not before
// a first step.
bool FlowSolver::take_back_jumped_step(SolveLoop& s) {
  const double r = s.rnorm[0];
  const double before = s.stepped_from;
  s.stepped_from = std::numeric_limits<double>::infinity();
  if (settings_.step_residual_jump <= 0.0 || !right_after_comparable_step(s, before) ||
      !(r > settings_.step_residual_jump * before))
    return false;
  back_off_to_good_state(s);
  ++s.report.steps_taken_back;
  if (settings_.print_every > 0)
    std::fprintf(stderr,
                 "iter %5d  residual up %.0f-fold in one step: back to the state before it, CFL "
                 "%.2e\n",
                 s.it, r / before, s.cfl);
  return true;
}

// The density residual against the run's reference (its largest, or the one passed in) and its
// best so far, whose state is kept; a march that has run away from that best goes back to it.
// True when it did (the iteration ends there).
bool FlowSolver::track_residual(SolveLoop& s) {
  const double r = s.rnorm[0];
  if (r > s.r_max)
    s.last_progress = s.it;  // still in the start-up transient
  s.r_max = std::max(s.r_max, r);
  // (a start with no density residual at all, e.g. fluid at rest behind a pressure jump,
  // has no reference yet)
  s.report.residual_drop = s.r_max > 0.0 ? r / s.r_max : 1.0;
  const bool diverged =
      s.diverged_march.diverged(s.newton_from != 0, s.cfl, settings_.cfl_start, r, s.r_min);
  // (a zero residual, the uniform state of a cold start, is no minimum to make progress from:
  // counted as one, it made every later iteration a stall and halved the CFL ceiling every
  // cfl_stall_iterations)
  if (r < s.r_min && r > 0.0) {
    s.r_min = r;
    s.last_minimum = s.it;
    s.last_progress = s.it;
    s.best_u = u_;
    s.best_nu = turbulence_snapshot();
    s.best_iteration = s.it;
  } else if (diverged && !s.best_u.empty() && s.report.best_state_restarts < kBestStateRestarts) {
    // The march diverged: relaxation and SER have held the CFL below its start value while
    // the residual ran away from its best. Left alone it does not come back (nasa-2dcd NPR
    // 2.46, defect correction with a live limiter after three failed Newton phases: one wall
    // node at the separation relaxed to nothing, the CFL fell to 1e-2 and the residual rose
    // from 2e4 to 1e10 over 600 iterations). Back to the best state, limiter live, the CFL
    // number from its start value and half the ceiling. (Sent back at the first such
    // iteration, NPARC 0.75 on 240 x 60 took 105 iterations instead of 99: DivergedMarch.)
    ++s.report.best_state_restarts;
    s.cfl_ceiling = std::max(settings_.cfl_start, 0.5 * s.cfl_ceiling);
    if (settings_.print_every > 0)
      std::fprintf(stderr,
                   "iter %5d  diverged (residual %.2e, %.0f times its best, CFL %.2e): back to "
                   "the state of iteration %d, CFL ceiling %.2e\n",
                   s.it, r, r / s.r_min, s.cfl, s.best_iteration, s.cfl_ceiling);
    u_ = s.best_u;
    if (!s.best_nu.empty())
      restore_turbulence(s.best_nu);
    limiter_frozen_ = false;
    s.cfl = settings_.cfl_start;
    s.cfl_scale = 1.0;
    s.last_progress = s.last_minimum = s.it;
    return true;
  }
  return false;
}

// Halve the CFL ceiling on a stall at (near) it: no new minimum for cfl_stall_iterations, or,
// with Newton-Krylov steps, a residual creeping down by less than a factor 2 over twice that
// (see SolverSettings::cfl_stall_iterations).
void FlowSolver::cut_cfl_ceiling_on_stall(SolveLoop& s) {
  const int it = s.it;
  if (settings_.cfl_stall_iterations > 0 && it - s.last_progress > settings_.cfl_stall_iterations) {
    // only a stall at (near) the ceiling is a large-CFL limit cycle; a low CFL is SER's doing
    if (s.cfl >= 0.5 * s.cfl_ceiling)
      s.cfl_ceiling = std::max(0.5 * s.cfl_ceiling, settings_.cfl_start);
    s.last_progress = it;
  }
  s.residual_by_iteration.push_back(s.rnorm[0]);
  const int window = 2 * settings_.cfl_stall_iterations;
  if (newton_krylov_step(s) && window > 0 && it - s.last_slow_cut >= window &&
      static_cast<int>(s.residual_by_iteration.size()) > window &&
      s.rnorm[0] > 0.5 * s.residual_by_iteration[s.residual_by_iteration.size() - 1 - window]) {
    // Matrix-free (near-Newton) steps: a residual creeping down by less than a factor 2 over
    // the window at the ceiling is as much a stall as none at all, but sets a new minimum
    // every few iterations. Measured on nasa-2dcd SMOKE at NPR 2.412: 9.8 -> 7.7 over 250
    // iterations at CFL 1e4; the same state restarted (ceiling cut to 625 on the way) fell
    // to 2.8e-7 in 200.
    if (s.cfl >= 0.5 * s.cfl_ceiling)
      s.cfl_ceiling = std::max(0.5 * s.cfl_ceiling, settings_.cfl_start);
    s.last_slow_cut = it;
  }
}

// Freeze the limiter once the residual has dropped by limiter_freeze_drop or stopped reaching
// new minima (limiter chatter near shocks stalls convergence; the frozen limiter is a fixed,
// valid scheme). With after_limiter_freeze this starts the Newton-Krylov phase.
void FlowSolver::freeze_limiter(SolveLoop& s) {
  s.rises_at_ceiling =
      rises_at_ceiling(s.rises_at_ceiling, s.rnorm[0], s.r_previous, s.cfl, s.cfl_ceiling);
  if ((settings_.limiter_freeze_drop > 0.0 &&
       s.report.residual_drop < settings_.limiter_freeze_drop) ||
      (settings_.limiter_stall_iterations > 0 && s.newton_fallbacks < kNewtonFallbacks &&
       s.it - s.last_minimum > settings_.limiter_stall_iterations) ||
      (settings_.limiter_rise_iterations > 0 && s.newton_fallbacks < kNewtonFallbacks &&
       s.rises_at_ceiling >= settings_.limiter_rise_iterations)) {
    limiter_frozen_ = true;
  }
}

// A Newton-Krylov phase whose residual rose well above, or stayed above, its start is given up
// for defect correction from its start state. True when it was (the iteration ends there).
bool FlowSolver::abandon_failed_newton_phase(SolveLoop& s) {
  const int it = s.it;
  if (!(s.newton_from > 0 && settings_.matrix_free == MatrixFree::after_limiter_freeze &&
        (s.rnorm[0] > 3.0 * s.newton_start_residual ||
         (it - s.newton_from >= std::max(settings_.limiter_stall_iterations, 10) &&
          s.rnorm[0] > s.newton_start_residual)))) {
    return false;
  }
  // The Newton phase failed: the limiter froze inside a transient (nasa-2dcd NPR 2.412: the
  // stall rule froze it while the separation still moved, and the Newton steps relaxed to
  // nothing behind the lips). Back to its start, limiter live, defect correction, and a new
  // stall count before the limiter may freeze again. After the last allowed failure the
  // stall rule freezes it no more: there, defect correction with the live limiter converged
  // (423 iterations) where the frozen one had not after 770.
  ++s.newton_fallbacks;
  if (settings_.print_every > 0)
    std::fprintf(stderr,
                 "iter %5d  Newton-Krylov phase from iteration %d abandoned (residual %.2e "
                 "against %.2e at its start): back to that state, limiter live%s\n",
                 it, s.newton_from, s.rnorm[0], s.newton_start_residual,
                 s.newton_fallbacks < kNewtonFallbacks ? "" : ", defect correction from here on");
  u_ = s.newton_start_u;
  if (!s.newton_start_nu.empty())
    restore_turbulence(s.newton_start_nu);
  limiter_frozen_ = false;
  s.newton_from = 0;
  s.last_minimum = s.last_progress = it;
  s.cfl_scale *= 0.5;
  s.cfl = std::max(settings_.cfl_start, 0.5 * s.newton_start_cfl);
  s.report.newton_fallbacks = s.newton_fallbacks;
  return true;
}

// This iteration's CFL number: the larger of switched evolution relaxation (Mulder and van
// Leer 1985) and the adaptive law, limited by cfl_growth and the ceiling (from the second
// iteration on); then this residual becomes the previous one for the next iteration.
void FlowSolver::update_cfl(SolveLoop& s) {
  const double r = s.rnorm[0];
  if (s.it > 1) {
    const double ser = s.r_max > 0.0 && r > 0.0 ? settings_.cfl_start * s.cfl_scale *
                                                      std::pow(s.r_max / r, settings_.ser_exponent)
                                                : settings_.cfl_start * s.cfl_scale;
    double adaptive = 0.0;
    if (settings_.cfl_adaptive_growth > 1.0) {
      // grow while the Newton updates are taken whole and the residual does not run away
      const bool healthy = s.last_omega >= 1.0 && !s.last_linear_failed &&
                           r <= settings_.cfl_adaptive_residual_rise * s.r_previous;
      adaptive = healthy ? s.cfl * settings_.cfl_adaptive_growth : s.cfl * 0.7;
    }
    // the Newton-Krylov phase after the limiter froze, every equation in its step: ceiling and
    // SER from the phase's start, raised by its residual drop
    // (SolverSettings::newton_cfl_follows_drop)
    double ceiling = s.cfl_ceiling;
    double ser_newton = 0.0;
    if (settings_.newton_cfl_follows_drop && s.newton_from > 0 && !segregated_turbulence_step(s) &&
        r > 0.0 && r < s.newton_start_residual) {
      const double drop = s.newton_start_residual / r;
      ceiling = s.cfl_ceiling * drop;
      ser_newton = s.newton_start_cfl * drop;
    }
    const double grown =
        std::min({std::max({ser, adaptive, ser_newton}), s.cfl * settings_.cfl_growth, ceiling});
    // Not past a step the linear solver could not solve: after an assembled solve that stopped
    // above its tolerance the CFL number does not grow. The residual-based SER would raise it
    // again, and the next solves failed further (NPARC 0.75 480 x 120: GMRES at its 80-iteration
    // limit twice at CFL 3,900-5,800, the residual then up fivefold and the CFL number cut).
    s.cfl = s.last_linear_short ? std::min(grown, s.cfl) : grown;
    s.cfl = std::max(s.cfl, 1e-3);
  }
  s.r_previous = r;
}

// The iteration's history record, from its residual and CFL number (the step fills in the
// rest).
void FlowSolver::begin_record(SolveLoop& s) {
  s.rec = IterationRecord{};
  s.rec.iteration = s.it;
  s.rec.residual = s.rnorm;
  s.rec.cfl = s.cfl;
  s.report.residual_reference = s.r_max;
}

// Wall-pressure stationarity (SolverSettings::stationary_tolerance): every wall pressure and the
// wall pressure force changing by less than the tolerance per iteration, for
// stationary_iterations steps that moved the state.
bool FlowSolver::wall_stationary(SolveLoop& s) {
  SolveReport& report = s.report;
  bool stationary = false;
  if (settings_.stationary_tolerance > 0.0 && !s.wall_nodes.empty()) {
    std::vector<double> wall_p(s.wall_nodes.size());
    for (std::size_t k = 0; k < s.wall_nodes.size(); ++k)
      wall_p[k] = w_[s.wall_nodes[k]][3];
    Vec2 force{};
    for (const BoundaryFace* face : s.wall_faces)
      force = force + w_[face->node][3] * face->normal;
    if (s.wall_p_previous.size() == wall_p.size()) {
      double dp = 0.0;
      for (std::size_t k = 0; k < wall_p.size(); ++k)
        dp = std::max(dp, std::abs(wall_p[k] - s.wall_p_previous[k]));
      report.wall_pressure_change = dp / settings_.reference_state[3];
      report.wall_force_change =
          norm(force - s.wall_force_previous) / std::max(norm(force), 1e-300);
      const bool small = report.wall_pressure_change < settings_.stationary_tolerance &&
                         report.wall_force_change < settings_.stationary_tolerance;
      // A step that could not move the state is no sign of stationarity: a linear solve that
      // made no headway (GMRES stagnating), a CFL number collapsed below its start value, or
      // updates relaxed away in a sizeable region. (A diverged second-order run at NPR 2.412,
      // frozen at CFL 3e-3, was otherwise reported converged.)
      const bool moving = report.history.empty() ||
                          (report.history.back().linear_residual <= 0.5 &&
                           report.history.back().cfl >= settings_.cfl_start && s.last_omega >= 0.5);
      s.stationary_count = small && moving ? s.stationary_count + 1 : 0;
      stationary = s.stationary_count >= settings_.stationary_iterations && s.it > s.ramp_end;
    }
    s.wall_p_previous = std::move(wall_p);
    s.wall_force_previous = force;
  }
  return stationary;
}

// The convergence test on the state this iteration started from: stationarity or the residual
// drop (after the inflow ramp, and at the CFL ceiling where asked). True when converged; the
// record is then the run's last.
bool FlowSolver::check_convergence(SolveLoop& s) {
  SolveReport& report = s.report;
  const bool stationary = wall_stationary(s);
  const bool past_transient = !settings_.residual_drop_at_cfl_ceiling || s.cfl >= s.cfl_ceiling;
  if (stationary ||
      (s.r_max > 0.0 && report.residual_drop <= settings_.residual_drop && s.it > s.ramp_end &&
       (s.it > 1 || settings_.residual_reference > 0.0) && past_transient)) {
    report.converged_by_stationarity = stationary && report.residual_drop > settings_.residual_drop;
    report.converged = true;
    s.rec.wall_time =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - s.start).count();
    report.history.push_back(s.rec);
    report.iterations = s.it - 1;
    return true;
  }
  return false;
}

// The restart of an assembled solve (settings.gmres_restart, 0: by the order). At first order the
// matrix is the residual's own Jacobian, so the step is Newton's once the CFL number is high, and
// GMRES keeps its whole basis, as the Newton-Krylov steps do: restarted at 20, NPARC 0.75 480 x
// 120's first-order stage ran into the 80-iteration limit twice at CFL 3.9e3, short of its
// tolerance (578 GMRES iterations in that stage against 413). A second-order defect-correction
// step solves only the first-order approximation of its Jacobian and keeps GMRES(20): with the
// whole basis there too, nasa-2dcd NPR 2.412 (segregated SA) lost its way in the second-order
// stage (the CFL number collapsed at iteration 711, session 44).
int FlowSolver::assembled_solve_restart() const {
  if (settings_.gmres_restart > 0)
    return settings_.gmres_restart;
  return settings_.order == 1 ? settings_.gmres_max_iterations : 20;
}

// The implicit step's linear system: V/dt from the CFL number, the first-order Jacobian (with
// the nu_tilde rows and cross blocks for a coupled step), the right-hand side -R with the strong
// conditions of fixed nodes and walls, and its ILU factors; then the solve, by Newton-Krylov or
// defect correction (newton_krylov_step()), into s.du.
void FlowSolver::linear_step(SolveLoop& s) {
  const int n = s.n, nb = s.nb;
  // the loops over nodes here are threaded: serial, they were 0.4 % of a two-thread run on
  // nasa-2dcd's case mesh, with the second thread idle
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i)
    s.diag_scale[i] = spectral_radius_[i] / s.cfl;  // V / dt
  assemble_jacobian(s.diag_scale);
  if (s.coupled) {
    s.rec.turbulence_residual = turbulence_residual_norm();
    turbulence_residual(true, &s.diag_scale);
    assemble_coupled_jacobian();
  }
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    double* rhs_i = s.rhs.data() + nb * static_cast<std::size_t>(i);
    for (int v = 0; v < 4; ++v)
      rhs_i[v] = fixed_node_[i] ? fixed_u_[i][v] - u_[i][v] : -res_[i][v];
    if (s.coupled)
      rhs_i[4] = -sa_row_scale_ * sa_res_[i];
    const int b = wall_node_bc_[i];
    if (b >= 0) {
      // strong conditions: drive momentum (and rho E - rho cv Tw) to zero
      rhs_i[1] = -u_[i][1];
      rhs_i[2] = -u_[i][2];
      if (bcs_[b].kind == BcKind::wall_isothermal) {
        rhs_i[3] = -(u_[i][3] - u_[i][0] * gas_.cv() * wall_temperature_at(b, i));
      }
    }
  }
  factorize_preconditioner();
  if (newton_krylov_step(s)) {
    s.lin = newton_krylov_solve(s);
  } else {
    s.lin = gmres(system_matrix(), preconditioner(), s.rhs, s.du, settings_.linear_tolerance,
                  assembled_solve_restart(), settings_.gmres_max_iterations, gmres_workspace_);
  }
  s.rec.linear_iterations = s.lin.iterations;
  s.rec.linear_residual = s.lin.relative_residual;
  s.last_linear_failed = !(s.lin.relative_residual <= kLinearSolveFailed);
  s.last_linear_short =
      !newton_krylov_step(s) && !(s.lin.relative_residual <= settings_.linear_tolerance);
  s.report.linear_iterations += s.lin.iterations;
}

void FlowSolver::factorize_preconditioner() {
  if (settings_.multigrid_levels > 1) {
    AggregationMultigrid::Options options;
    options.max_levels = settings_.multigrid_levels;
    options.post_smoother = settings_.multigrid_post_smoother;
    multigrid_.setup(system_matrix(), settings_.ilu_partitions, settings_.ilu_fill_level, options);
  } else {
    ilu_.factorize(system_matrix(), settings_.ilu_partitions, settings_.ilu_fill_level);
  }
}

const Preconditioner& FlowSolver::preconditioner() const {
  if (settings_.multigrid_levels > 1)
    return multigrid_;
  return ilu_;
}

// The Newton-Krylov step: the start of a Newton phase (its state kept for a fallback), the
// Eisenstat-Walker tolerance, GMRES on the matrix-free operator, and the state's own residual
// back in place of the last perturbed one.
GmresResult FlowSolver::newton_krylov_solve(SolveLoop& s) {
  const int it = s.it;
  if (s.newton_from == 0 && settings_.matrix_free == MatrixFree::after_limiter_freeze) {
    s.newton_from = s.report.newton_from = it;
    s.newton_start_u = u_;
    s.newton_start_nu = turbulence_snapshot();
    s.newton_start_residual = s.r_previous;
    s.newton_start_cfl = s.cfl;
    if (settings_.print_every > 0)
      std::fprintf(stderr, "iter %5d  limiter frozen: Newton-Krylov steps from here (drop %.2e)\n",
                   it, s.report.residual_drop);
  }
  double forcing = settings_.matrix_free_linear_tolerance;
  if (settings_.eisenstat_walker && s.newton_residual_previous > 0.0) {
    // Eisenstat and Walker 1996 (SIAM J. Sci. Comput. 17:16), choice 2 with gamma 0.9,
    // alpha 2 and its safeguard: solve tighter as the residual falls faster, so the
    // inexact Newton steps converge superlinearly instead of at the fixed tolerance's rate
    const double ratio = s.r_previous / s.newton_residual_previous;
    forcing = 0.9 * ratio * ratio;
    const double safeguard = 0.9 * s.forcing_previous * s.forcing_previous;
    if (safeguard > 0.1)
      forcing = std::max(forcing, safeguard);
    forcing =
        std::clamp(forcing, settings_.eisenstat_walker_min, settings_.matrix_free_linear_tolerance);
  }
  s.newton_residual_previous = s.r_previous;
  s.forcing_previous = forcing;
  // no restart: restarted GMRES(20) stagnated outright (relative residual 1.0 after 80
  // iterations) on nasa-2dcd at CFL 1e4 where the full basis converged in 137-183
  const GmresResult lin =
      gmres(matrix_free_operator(s.diag_scale), preconditioner(), s.rhs, s.du, forcing,
            std::max(settings_.gmres_restart, settings_.gmres_max_iterations),
            settings_.gmres_max_iterations, gmres_workspace_);
  compute_residual(false);  // back to the state's own residual, gradients and viscosities
  return lin;
}

// The fraction omega of node i's update du_i that is taken, and the relaxed conservative state
// un it gives: the relative change of density and pressure (and, coupled, of nu_tilde) limited,
// then omega halved until the state is physical (0: the node keeps its state).
double FlowSolver::node_relaxation(int i, const double* du_i, bool coupled, State& un) const {
  un = u_[i];
  for (int v = 0; v < 4; ++v)
    un[v] += du_i[v];
  const State wn = gas_.primitive(un);
  const State& wo = w_[i];
  const double change = std::max(std::abs(wn[0] - wo[0]) / wo[0], std::abs(wn[3] - wo[3]) / wo[3]);
  double omega_i = 1.0;
  if (!std::isfinite(change))
    omega_i = 0.0;
  else if (change > settings_.max_relative_update)
    omega_i = settings_.max_relative_update / change;
  if (coupled && wall_node_bc_[i] < 0) {
    if (!std::isfinite(du_i[4]))
      omega_i = 0.0;
    else if (!settings_.limit_turbulence_alone)
      omega_i = turbulence_relaxation(i, du_i[4], omega_i);
  }
  // The primitive change is not linear in omega (kinetic energy): halve omega until the
  // relaxed state is physical and within the allowed change, rather than freezing the node
  // (a frozen node near a near-vacuum lip corner never recovers, its residual grows and the
  // SER ramp then collapses the CFL everywhere).
  for (int halving = 0;; ++halving) {
    for (int v = 0; v < 4; ++v)
      un[v] = u_[i][v] + omega_i * du_i[v];
    const double p_new =
        (gas_.gamma - 1.0) * (un[3] - 0.5 * (un[1] * un[1] + un[2] * un[2]) / un[0]);
    const bool ok = un[0] > 0.0 && p_new > kPressureFloor * un[3] &&
                    std::abs(p_new - wo[3]) <= 2.0 * settings_.max_relative_update * wo[3];
    if (ok)
      break;
    if (halving == 12 || omega_i == 0.0) {
      omega_i = 0.0;
      un = u_[i];
      break;
    }
    omega_i *= 0.5;
  }
  return omega_i;
}

// The fraction of a coupled step's nu_tilde update that may be taken at node i, at most
// omega_i: nu_tilde may grow by a factor 1 + max_turbulence_update per step and fall by the same
// fraction of its scale |nu_tilde| + nu, since the Newton step of the source terms overshoots
// where production outruns destruction (a physicality-based step limit). By default it relaxes
// the whole node (node_relaxation); with limit_turbulence_alone nu_tilde's update only. Whole
// nodes held the mean flow back with nu_tilde: on nasa-2dcd NPR 8.91 (lines ordering) the
// coupled steps right after the first-order start took 0.09-0.47 of their update for 13
// iterations and the CFL number was 670 at the 15th; with nu_tilde alone limited every step
// was taken whole, the CFL number was 4,600 there and the second-order stage took 35
// iterations instead of 40.
double FlowSolver::turbulence_relaxation(int i, double du_nu, double omega_i) const {
  const double scale = std::abs(nu_tilde_[i]) + sa_nu_[i];
  const double change_nu = std::abs(du_nu) / scale;
  return change_nu * omega_i > settings_.max_turbulence_update
             ? settings_.max_turbulence_update / change_nu
             : omega_i;
}

// The update u += omega du, relaxed node by node so that a near-vacuum corner does not hold
// back the rest of the domain; then the strong conditions, and the least relaxation for the
// report.
void FlowSolver::relax_update(SolveLoop& s) {
  const int n = s.n, nb = s.nb;
  const bool coupled = s.coupled;
  // Relaxation, node by node: limit the relative change of density and pressure, and leave
  // a node unchanged if even the limited update is not physical. Local relaxation acts like
  // a local time step: a near-vacuum corner does not hold back the rest of the domain.
  double omega_min = 1.0;
  int omega_node = -1;
  int limited = 0;
  s.u_good = u_;
  if (coupled)
    s.nu_good = turbulence_snapshot();
  for (int i = 0; i < n; ++i) {
    const double* du_i = s.du.data() + nb * static_cast<std::size_t>(i);
    State un;
    const double omega_i = node_relaxation(i, du_i, coupled, un);
    u_[i] = un;
    if (coupled) {
      // the mean flow's fraction of the Newton step for nu_tilde (or less, see
      // turbulence_relaxation); strong 0 on no-slip walls
      if (wall_node_bc_[i] >= 0)
        nu_tilde_[i] = 0.0;
      else if (std::isfinite(du_i[4]))
        nu_tilde_[i] +=
            (settings_.limit_turbulence_alone ? turbulence_relaxation(i, du_i[4], omega_i)
                                              : omega_i) *
            du_i[4];
    }
    if (omega_i < 1.0)
      ++limited;
    if (omega_i < omega_min) {
      omega_min = omega_i;
      omega_node = i;
    }
  }
  apply_strong_conditions(u_);
  s.report.least_relaxation = omega_min;
  if (omega_node >= 0)
    s.report.least_relaxed_at = dual_.coords[omega_node];
  s.omega_min = omega_min;
  s.omega_node = omega_node;
  s.limited = limited;
}

// What the step tells the CFL control: a non-physical result goes back to the state before it
// with a tenth of the CFL number; a linearisation far off in a sizeable region, or a failed
// linear solve, halves it. The relaxation seen by the next CFL update is set here too.
void FlowSolver::accept_or_reject_step(SolveLoop& s) {
  const double limited_fraction = static_cast<double>(s.limited) / s.n;
  s.rec.relaxation = s.omega_min;
  // CFL control sees a limited update only if it concerns more than a few nodes
  s.last_omega = limited_fraction <= settings_.relaxed_fraction_tolerated ? 1.0 : s.omega_min;
  if (!physical(u_)) {
    u_ = s.u_good;
    if (s.coupled)
      restore_turbulence(s.nu_good);
    s.cfl_scale *= 0.1;
    s.cfl *= 0.1;
    ++s.report.backoffs;
  } else if ((limited_fraction > settings_.relaxed_fraction_tolerated && s.omega_min < 0.5) ||
             s.last_linear_failed) {
    if (s.last_linear_failed && exact_roe_jacobian_) {
      // Across a forming shock ILU of the exact Roe Jacobian can fail where that of the frozen
      // one still serves (NPARC 0.75, 480 x 120, first order: GMRES at 0.5-0.6 after 80
      // iterations as the shock settled, 1,570 iterations in all against 124).
      exact_roe_jacobian_ = false;
      s.report.roe_jacobian_frozen_from = s.it;
      if (settings_.print_every > 0)
        std::fprintf(stderr,
                     "iter %5d  linear solve failed with the exact Roe Jacobian: frozen "
                     "dissipation matrix from here on\n",
                     s.it);
    }
    // the linearisation was far off in a sizeable region, or the linear solve could not
    // solve it: slow the ramp down. (A failed solve moves the state little, so neither the
    // relaxation nor the residual sees it; NPARC 0.75 on 480 x 120 took 22 such steps at CFL
    // 1e4 with GMRES at a relative residual of 1.0, then blew up and took 60 to recover.)
    s.cfl_scale *= 0.5;
    s.cfl *= 0.5;
  }
}

// The node with the largest density residual per volume: the first thing to look at when a
// run stalls (progress line, report of a run that did not converge).
int FlowSolver::worst_residual_node(int v) const {
  int worst = 0;
  double largest = -1.0;
  for (int i = 0; i < dual_.num_nodes; ++i) {
    double r = 0.0;
    if (v == 4) {
      if (wall_node_bc_[i] >= 0)
        continue;  // nu_tilde is imposed there (turbulence_residual_norm())
      r = std::abs(sa_res_[i]);
    } else {
      if (!residual_row_counted(i, v))
        continue;
      r = std::abs(res_[i][v]);
    }
    r /= dual_.volume[i];
    if (r > largest) {
      largest = r;
      worst = i;
    }
  }
  return worst;
}

// The iteration's record into the history, and the progress line every print_every iterations.
void FlowSolver::report_progress(SolveLoop& s) {
  const int it = s.it;
  const double omega = s.omega_min;
  s.rec.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - s.start).count();
  s.report.history.push_back(s.rec);
  s.report.iterations = it;
  if (settings_.print_every > 0 && (it % settings_.print_every == 0 || it == 1)) {
    std::fprintf(stderr, "iter %5d  res(rho) %.3e  drop %.2e  cfl %.2e  omega %.2f  lin %3d (%.1e)",
                 it, s.rnorm[0], s.report.residual_drop, s.cfl, omega, s.lin.iterations,
                 s.lin.relative_residual);
    if (settings_.turbulent)
      std::fprintf(stderr, sst() ? "  res(k) %.2e" : "  res(nu_t) %.2e", s.rec.turbulence_residual);
    // where the density residual is largest: the first thing to look at when it stalls
    const int worst = worst_residual_node();
    std::fprintf(stderr, "  max at (%.4g, %.4g)", dual_.coords[worst].x, dual_.coords[worst].y);
    if (s.omega_node >= 0) {
      std::fprintf(stderr, "  omega min at (%.4g, %.4g)", dual_.coords[s.omega_node].x,
                   dual_.coords[s.omega_node].y);
    }
    std::fprintf(stderr, "\n");
  }
  if (settings_.on_iteration)
    settings_.on_iteration(it);
}

// Give up after more than 20 returns to the last good state, or when the CFL has collapsed:
// the pseudo-time march no longer moves.
bool FlowSolver::march_stopped(SolveLoop& s) {
  if (s.report.backoffs > 20)
    return true;
  s.collapsed = s.cfl < 1e-3 * settings_.cfl_start ? s.collapsed + 1 : 0;
  return s.collapsed > 10;
}

// The report's closing part: for a run that did not converge, the last physical state back in
// place with its residual, why it stopped and where; for every run, the times and counts.
void FlowSolver::finish_run(SolveLoop& s) {
  SolveReport& report = s.report;
  if (!report.converged) {
    compute_residual(!limiter_frozen_);
    if (!physical(u_)) {
      u_ = s.u_good;
      if (s.coupled)
        restore_turbulence(s.nu_good);
      compute_residual(!limiter_frozen_);
    }
    report.stop_reason =
        report.backoffs > 20 ? "more than 20 returns to the last good state (non-physical updates)"
        : s.collapsed > 10
            ? "the CFL number collapsed below 1e-3 of its start value"
            : "iteration limit (" + std::to_string(settings_.max_iterations) + ") reached";
    for (int v = 0; v < 5; ++v) {
      const bool sa = v == 4 && settings_.turbulent && !sst();
      report.largest_residual_at[v] =
          v < 4 || sa ? dual_.coords[worst_residual_node(v)] : report.largest_residual_at[0];
    }
    report.worst_residual_at = report.largest_residual_at[0];
  }
  report.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - s.start).count();
  report.final_cfl = s.cfl;
  report.residual_evaluations = residual_evaluations_ - s.evaluations_before;
  report.residual_seconds = residual_seconds_ - s.residual_seconds_before;
}

BoundaryIntegral FlowSolver::boundary_integral(int curve) {
  for (int i = 0; i < dual_.num_nodes; ++i)
    w_[i] = gas_.primitive(u_[i]);
  BoundaryIntegral total;
  for (const auto& face : dual_.boundary_faces) {
    if (face.curve != curve)
      continue;
    const State f = boundary_flux(gas_, bcs_[curve], w_[face.node], face.normal, face.node,
                                  settings_.entropy_fix);
    total.mass_flow += f[0];
    total.force.x += f[1];
    total.force.y += f[2];
    total.energy_flow += f[3];
  }
  return total;
}

WallTrace FlowSolver::wall_trace(int curve) {
  return wall_traces({curve}).front();
}

std::vector<WallTrace> FlowSolver::wall_traces(const std::vector<int>& curves) {
  // primitives and gradients once for all curves (a time-accurate run takes every wall's
  // trace at every step)
  const ScopedThreads threads(settings_.threads);
  for (int i = 0; i < dual_.num_nodes; ++i)
    w_[i] = gas_.primitive(u_[i]);
  lsq_gradients(dual_, lsq_, w_, grad_);
  std::vector<WallTrace> traces;
  traces.reserve(curves.size());
  for (int curve : curves)
    traces.push_back(trace_of(curve));
  return traces;
}

WallTrace FlowSolver::trace_of(int curve) const {
  const auto& edges = mesh_.boundaries.at(curve).edges;
  WallTrace t;
  if (edges.empty())
    return t;
  t.node.push_back(edges.front()[0]);
  for (const auto& e : edges)
    t.node.push_back(e[1]);
  std::vector<int> external_node(t.node.size());
  for (std::size_t k = 0; k < t.node.size(); ++k)
    external_node[k] = old_of_new_[t.node[k]];
  // outward normal per node: sum of its boundary faces on this curve
  std::vector<Vec2> normal(t.node.size());
  std::vector<Vec2> tangent(t.node.size());
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const Vec2 a = dual_.coords[edges[k][0]];
    const Vec2 b = dual_.coords[edges[k][1]];
    tangent[k] = tangent[k] + (b - a);
    tangent[k + 1] = tangent[k + 1] + (b - a);
  }
  for (const auto& face : dual_.boundary_faces) {
    if (face.curve != curve)
      continue;
    const int k = face.curve_edge;
    const int slot = (face.node == edges[k][0]) ? k : k + 1;
    normal[slot] = normal[slot] + face.normal;
  }
  double s = 0.0;
  for (std::size_t k = 0; k < t.node.size(); ++k) {
    const int i = t.node[k];
    if (k > 0)
      s += norm(dual_.coords[i] - dual_.coords[t.node[k - 1]]);
    const State& w = w_[i];
    t.s.push_back(s);
    t.x.push_back(dual_.coords[i].x);
    t.y.push_back(dual_.coords[i].y);
    t.pressure.push_back(w[3]);
    const double temp = gas_.temperature(w);
    t.temperature.push_back(temp);
    double shear = 0.0, heat = 0.0;
    if (settings_.viscous) {
      const auto& g = grad_[i];
      const double nn = norm(normal[k]);
      const Vec2 n{normal[k].x / nn, normal[k].y / nn};
      const double tl = norm(tangent[k]);
      const Vec2 tv{tangent[k].x / tl, tangent[k].y / tl};
      const double mu = settings_.viscosity.viscosity(temp);
      const double div = g[2] + g[5];
      const double txx = mu * (2.0 * g[2] - 2.0 / 3.0 * div);
      const double tyy = mu * (2.0 * g[5] - 2.0 / 3.0 * div);
      const double txy = mu * (g[3] + g[4]);
      // traction on the wall = -(tau . n_out) (n_out leaves the fluid)
      shear = -((txx * n.x + txy * n.y) * tv.x + (txy * n.x + tyy * n.y) * tv.y);
      const double dtdx = (g[6] - temp * gas_.R * g[0]) / (w[0] * gas_.R);
      const double dtdy = (g[7] - temp * gas_.R * g[1]) / (w[0] * gas_.R);
      const double k_cond = mu * gas_.cp() / settings_.viscosity.prandtl;
      heat = -k_cond * (dtdx * n.x + dtdy * n.y);
    }
    t.shear_stress.push_back(shear);
    t.heat_flux.push_back(heat);
    const double length = norm(normal[k]);
    t.normal.push_back(length > 0.0 ? Vec2{normal[k].x / length, normal[k].y / length}
                                    : Vec2{0.0, 0.0});
  }
  t.node = std::move(external_node);
  return t;
}

}  // namespace tfmb::flow
