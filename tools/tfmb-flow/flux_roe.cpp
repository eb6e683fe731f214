#include "flux_roe.hpp"

#include <algorithm>

#include "tfmb/common/dual.hpp"

namespace tfmb::flow {

namespace {

// The flux below is written once on its scalar type T: double for the flux, Dual<8> for its
// exact derivative with respect to both sides' conservative variables.
template <class T>
using StateOf = std::array<T, 4>;

template <class T>
struct RoeAverage {
  T rho, u, v, h, c, vn, q2;
  double nx, ny;             // unit normal
  T abs_l1, abs_l2, abs_l3;  // |V-c|, |V|, |V+c| after the entropy fix
};

// Harten's smoothing of |lambda| near zero (Blazek 2015, eq. 4.93).
template <class T>
T harten(const T& lambda, const T& delta) {
  using std::abs;
  const T a = abs(lambda);
  return a >= delta ? a : 0.5 * (lambda * lambda + delta * delta) / delta;
}

// |A_Roe| times a jump given as primitive increments (Blazek 2015, eqs. 4.90-4.92). Scaled by the
// face length outside. R is the Roe state's scalar, J the jump's (a frozen |A_Roe| applied to a
// double jump, or the whole product differentiated).
template <class R, class J>
StateOf<J> dissipation(const RoeAverage<R>& r, const J& drho, const J& du, const J& dv,
                       const J& dp) {
  const J dvn = r.nx * du + r.ny * dv;
  const R c2 = r.c * r.c;
  const J a1 = r.abs_l1 * (dp - r.rho * r.c * dvn) / (2.0 * c2);
  const J a3 = r.abs_l3 * (dp + r.rho * r.c * dvn) / (2.0 * c2);
  const J a2 = r.abs_l2 * (drho - dp / c2);
  const R a2r = r.abs_l2 * r.rho;
  return {a1 + a2 + a3,
          a1 * (r.u - r.c * r.nx) + a2 * r.u + a2r * (du - r.nx * dvn) + a3 * (r.u + r.c * r.nx),
          a1 * (r.v - r.c * r.ny) + a2 * r.v + a2r * (dv - r.ny * dvn) + a3 * (r.v + r.c * r.ny),
          a1 * (r.h - r.c * r.vn) + a2 * 0.5 * r.q2 + a2r * (r.u * du + r.v * dv - r.vn * dvn) +
              a3 * (r.h + r.c * r.vn)};
}

// Roe averages (Blazek 2015, eq. 4.89) and the smoothed eigenvalues at the unit normal.
template <class T>
RoeAverage<T> roe_average(const PerfectGas& gas, const StateOf<T>& wl, const StateOf<T>& wr,
                          double nx, double ny, double s, double entropy_fix) {
  using std::sqrt;
  RoeAverage<T> r;
  r.nx = nx / s;
  r.ny = ny / s;
  const T sl = sqrt(wl[0]);
  const T sr = sqrt(wr[0]);
  const T wgt = 1.0 / (sl + sr);
  const T hl = gas.total_enthalpy(wl);
  const T hr = gas.total_enthalpy(wr);
  r.rho = sl * sr;
  r.u = (sl * wl[1] + sr * wr[1]) * wgt;
  r.v = (sl * wl[2] + sr * wr[2]) * wgt;
  r.h = (sl * hl + sr * hr) * wgt;
  r.q2 = r.u * r.u + r.v * r.v;
  const T c2 = (gas.gamma - 1.0) * (r.h - 0.5 * r.q2);
  const T c2_floor = 1e-12 * r.h;
  r.c = sqrt(c2 > c2_floor ? c2 : c2_floor);
  r.vn = r.u * r.nx + r.v * r.ny;
  const T delta = entropy_fix * r.c;
  r.abs_l1 = harten<T>(r.vn - r.c, delta);
  r.abs_l2 = harten<T>(r.vn, delta);
  r.abs_l3 = harten<T>(r.vn + r.c, delta);
  return r;
}

template <class T>
StateOf<T> roe_flux_of(const PerfectGas& gas, const StateOf<T>& wl, const StateOf<T>& wr, double nx,
                       double ny, double entropy_fix, RoeAverage<T>* average = nullptr) {
  const double s = std::sqrt(nx * nx + ny * ny);
  const RoeAverage<T> r = roe_average(gas, wl, wr, nx, ny, s, entropy_fix);
  const StateOf<T> fl = euler_flux(gas, wl, nx, ny);
  const StateOf<T> fr = euler_flux(gas, wr, nx, ny);
  const StateOf<T> d =
      dissipation<T, T>(r, wr[0] - wl[0], wr[1] - wl[1], wr[2] - wl[2], wr[3] - wl[3]);
  StateOf<T> f;
  for (int k = 0; k < 4; ++k)
    f[k] = 0.5 * (fl[k] + fr[k] - s * d[k]);
  if (average)
    *average = r;
  return f;
}

}  // namespace

State roe_flux(const PerfectGas& gas, const State& wl, const State& wr, double nx, double ny,
               double entropy_fix, RoeFluxJacobians* jac) {
  RoeAverage<double> r;
  const State f = roe_flux_of<double>(gas, wl, wr, nx, ny, entropy_fix, &r);
  if (jac) {
    const double s = std::sqrt(nx * nx + ny * ny);
    // Columns of |A_Roe|: the jump e_k in conservative variables, linearised at the Roe state.
    Block abs_a;
    const double g1 = gas.gamma - 1.0;
    for (int k = 0; k < 4; ++k) {
      const double du0 = k == 0 ? 1.0 : 0.0;
      const double du1 = k == 1 ? 1.0 : 0.0;
      const double du2 = k == 2 ? 1.0 : 0.0;
      const double du3 = k == 3 ? 1.0 : 0.0;
      const double drho = du0;
      const double du = (du1 - r.u * du0) / r.rho;
      const double dv = (du2 - r.v * du0) / r.rho;
      const double dp = g1 * (du3 - r.u * du1 - r.v * du2 + 0.5 * r.q2 * du0);
      const State col = dissipation<double, double>(r, drho, du, dv, dp);
      for (int row = 0; row < 4; ++row)
        abs_a[row * 4 + k] = s * col[row];
    }
    const Block al = euler_flux_jacobian(gas, wl, nx, ny);
    const Block ar = euler_flux_jacobian(gas, wr, nx, ny);
    for (int k = 0; k < 16; ++k) {
      jac->d_left[k] = 0.5 * (al[k] + abs_a[k]);
      jac->d_right[k] = 0.5 * (ar[k] - abs_a[k]);
    }
  }
  return f;
}

State roe_flux_exact(const PerfectGas& gas, const State& wl, const State& wr, double nx, double ny,
                     double entropy_fix, RoeFluxJacobians& jac) {
  using D = Dual<8>;
  const State ul = gas.conservative(wl);
  const State ur = gas.conservative(wr);
  StateOf<D> ul_d, ur_d;
  for (int k = 0; k < 4; ++k) {
    ul_d[k] = D::variable(k, ul[k]);
    ur_d[k] = D::variable(4 + k, ur[k]);
  }
  const StateOf<D> f =
      roe_flux_of<D>(gas, gas.primitive(ul_d), gas.primitive(ur_d), nx, ny, entropy_fix);
  State value;
  for (int row = 0; row < 4; ++row) {
    value[row] = f[row].v;
    for (int c = 0; c < 4; ++c) {
      jac.d_left[4 * row + c] = f[row].d[c];
      jac.d_right[4 * row + c] = f[row].d[4 + c];
    }
  }
  return value;
}

}  // namespace tfmb::flow
