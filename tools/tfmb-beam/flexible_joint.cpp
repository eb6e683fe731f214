#include "tfmb-beam/flexible_joint.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "tfmb-beam/hyper_dual.hpp"

namespace tfmb::beam {

double MeasureFunction::small_motion_limit() const {
  double v = 0.0;
  for (const MeasureTerm& t : terms)
    if (t.sigma_power == 0 && t.p_power == 0) v += t.coefficient;
  return v;  // the cosine factor is 1 at p = 0
}

std::string MeasureFunction::formula() const {
  std::ostringstream s;
  for (const MeasureTerm& t : terms) {
    if (t.coefficient == 0.0) continue;
    const bool first = s.tellp() == 0;
    if (!first) s << (t.coefficient < 0.0 ? " - " : " + ");
    const double c = first ? t.coefficient : std::abs(t.coefficient);
    const bool has_variable = t.sigma_power > 0 || t.p_power > 0;
    if (!has_variable || c != 1.0) s << c << (has_variable ? " " : "");
    if (t.sigma_power > 0) s << "sigma" << (t.sigma_power > 1 ? "^" + std::to_string(t.sigma_power) : "");
    if (t.sigma_power > 0 && t.p_power > 0) s << " ";
    if (t.p_power > 0) s << "p" << (t.p_power > 1 ? "^" + std::to_string(t.p_power) : "");
  }
  const std::string poly = s.tellp() == 0 ? "0" : s.str();
  if (!wm_cosine_factor) return poly;
  const std::string factor = "(1 - p^2/16)/(1 + p^2/16)";
  return poly == "1" ? factor : "(" + poly + ") " + factor;
}

namespace {

MeasureFunction constant(double c) { return MeasureFunction{{{c, 0, 0}}, false}; }
MeasureFunction one_plus(int sigma_power, int p_power) {
  return MeasureFunction{{{1.0, 0, 0}, {1.0, sigma_power, p_power}}, false};
}
MeasureFunction monomial(int sigma_power, int p_power) { return MeasureFunction{{{1.0, sigma_power, p_power}}, false}; }

}  // namespace

// The seed's Table 1 ("choices of parameters lambda and mu for the sixteen cases"), read from the
// OCR text: column a is lambda = 0, mu = 1 in every row; row 1 varies mu with p (mu = 1 + p^2,
// 1 + p^4, 1 + p^6, stated in the text), row 2 varies mu with sigma, row 3 varies lambda with
// sigma and row 4 varies lambda with p, mu = 1 (the text says which variable; the exponents of
// rows 2-4 are garbled and are our reading: sigma, sigma^2, sigma^3 and p^2, p^4, p^6).
MeasureFunctions seed_measure_functions(const std::string& name) {
  MeasureFunctions f;
  f.name = name;
  if (name == "default") {
    f.lambda = constant(0.0);
    f.mu = MeasureFunction{{{1.0, 0, 0}}, true};
    return f;
  }
  if (name.size() == 2 && name[0] >= '1' && name[0] <= '4' && name[1] >= 'a' && name[1] <= 'd') {
    const int row = name[0] - '0';
    const int col = name[1] - 'a';  // 0: a, 1: b, 2: c, 3: d
    f.lambda = constant(0.0);
    f.mu = constant(1.0);
    if (col == 0) return f;
    switch (row) {
      case 1: f.mu = one_plus(0, 2 * col); break;   // 1 + p^2, 1 + p^4, 1 + p^6
      case 2: f.mu = one_plus(col, 0); break;       // 1 + sigma, 1 + sigma^2, 1 + sigma^3
      case 3: f.lambda = monomial(col, 0); break;   // sigma, sigma^2, sigma^3
      case 4: f.lambda = monomial(0, 2 * col); break;  // p^2, p^4, p^6
    }
    return f;
  }
  std::string names;
  for (const auto& n : seed_measure_function_names()) names += (names.empty() ? "" : ", ") + n;
  throw std::invalid_argument("flexible joint measure functions '" + name + "' are not known; use one of " + names +
                              " or give lambda and mu as polynomial terms");
}

std::vector<std::string> seed_measure_function_names() {
  std::vector<std::string> n{"default"};
  for (char r = '1'; r <= '4'; ++r)
    for (char c = 'a'; c <= 'd'; ++c) n.push_back(std::string{r, c});
  return n;
}

void check_measure_functions(const MeasureFunctions& f) {
  auto check_powers = [&](const MeasureFunction& g, const char* which) {
    for (const MeasureTerm& t : g.terms) {
      if (t.sigma_power < 0 || t.p_power < 0)
        throw std::invalid_argument(std::string("flexible joint measure ") + which + " = " + g.formula() +
                                    ": powers of sigma and p must be >= 0");
      if (t.p_power % 2 != 0)
        throw std::invalid_argument(std::string("flexible joint measure ") + which + " = " + g.formula() + ": p^" +
                                    std::to_string(t.p_power) +
                                    " is an odd power of |p|, not differentiable at zero relative rotation; use even powers");
    }
  };
  check_powers(f.lambda, "lambda");
  check_powers(f.mu, "mu");
  // Seed eq. (18): the wryness k = mu p must tend to the infinitesimal rotation phi n.
  const double mu0 = f.mu.small_motion_limit();
  if (std::abs(mu0 - 1.0) > 1e-12)
    throw std::invalid_argument("flexible joint measure mu = " + f.mu.formula() + " tends to " + std::to_string(mu0) +
                                " for small motion; the seed's eq. (18) requires mu -> 1 (the wryness must tend to the "
                                "infinitesimal rotation)");
  // Seed eq. (19): for planar relative motion the stretch must stay normal to the rotation axis.
  const double lambda0 = f.lambda.small_motion_limit();
  if (std::abs(lambda0) > 1e-12)
    throw std::invalid_argument("flexible joint measure lambda = " + f.lambda.formula() + " tends to " +
                                std::to_string(lambda0) +
                                " for small motion; the seed's eq. (19) requires lambda -> 0 (the stretch must tend to "
                                "the relative displacement)");
}

FlexibleJointResponse evaluate_flexible_joint(const FlexibleJointLaw& law, const HandleState& k, const HandleState& l) {
  using H = Hyper<12>;
  Vec3<H> xk, xl, dk, dl;
  for (int i = 0; i < 3; ++i) {
    xk(i) = H::variable(i, k.position(i));
    dk(i) = H::variable(3 + i, 0.0);
    xl(i) = H::variable(6 + i, l.position(i));
    dl(i) = H::variable(9 + i, 0.0);
  }
  // Handle rotations after the spatial increments: R(d) R(c).
  const Vec3<H> ck = wm_compose<H>(k.rotation.cast<H>(), dk);
  const Vec3<H> cl = wm_compose<H>(l.rotation.cast<H>(), dl);
  // Relative rotation R_k^T R_l (first l, then the inverse of k), then resolved in the joint frame
  // B0: the parameters of B0^T R B0 are B0^T times those of R (seed eq. 3).
  const Vec3<H> rel = wm_compose<H>(cl, Vec3<H>(-ck));
  const Mat3<H> b0t = law.frame.transpose().cast<H>();
  const Vec3<H> p = b0t * rel;
  const Mat3<H> rk = wm_rotation<H>(ck);
  const Vec3<H> u = b0t * (rk.transpose() * (xl - xk));
  const Eigen::Matrix<H, 6, 1> e = flexible_joint_measures<H>(law, u, p);
  const Eigen::Matrix<H, 6, 1> de = law.stiffness.cast<H>() * e;
  const H energy = 0.5 * e.dot(de);

  FlexibleJointResponse r;
  r.energy = energy.v;
  for (int i = 0; i < 6; ++i) r.measures(i) = e(i).v;
  for (int i = 0; i < 3; ++i) {
    r.relative_displacement(i) = u(i).v;
    r.relative_rotation(i) = p(i).v;
  }
  for (int i = 0; i < 12; ++i) {
    r.force(i) = energy.g[i];
    for (int j = 0; j < 12; ++j) r.tangent(i, j) = energy.hess(i, j);
  }
  // The Hessian above is taken in the chart R(d) R; the solver updates R <- R(d) R once more, and
  // R(a) R(b) = R(a + b + a x b / 2 + ...), so the derivative of the forces along that update adds
  // -1/2 S(m) to each handle's rotation block (m: that handle's moment part of `force`).
  for (int block : {3, 9}) r.tangent.block<3, 3>(block, block) -= 0.5 * skew<double>(r.force.segment<3>(block));
  return r;
}

}  // namespace tfmb::beam
