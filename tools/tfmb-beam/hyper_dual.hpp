// Second-order forward automatic differentiation with a fixed number of variables.
//
// A Hyper<N> carries a value, its gradient with respect to N independent variables and the
// symmetric N x N Hessian (packed lower triangle). The beam element and the joints write their
// strains and constraint equations once, templated on the scalar; evaluating them with Hyper<N>
// gives the exact first and second derivatives needed for a consistent Newton tangent, without
// hand-derived linearisations that are easy to get subtly wrong (FORMULATION.md sec. 2 warns that
// the tangent of the objective interpolation is intricate).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>

namespace tfmb::beam {

template <int N>
struct Hyper {
  static constexpr int kPacked = N * (N + 1) / 2;
  double v = 0.0;
  std::array<double, N> g{};
  std::array<double, kPacked> h{};

  Hyper() = default;
  Hyper(double value) : v(value) {}  // NOLINT: implicit from double is the point of the type

  /// Independent variable number `index` with value `value`.
  static Hyper variable(int index, double value) {
    Hyper x(value);
    x.g[index] = 1.0;
    return x;
  }
  static constexpr int packed(int i, int j) { return i >= j ? i * (i + 1) / 2 + j : j * (j + 1) / 2 + i; }
  double hess(int i, int j) const { return h[packed(i, j)]; }

  Hyper& operator+=(const Hyper& o) {
    v += o.v;
    for (int i = 0; i < N; ++i) g[i] += o.g[i];
    for (int i = 0; i < kPacked; ++i) h[i] += o.h[i];
    return *this;
  }
  Hyper& operator-=(const Hyper& o) {
    v -= o.v;
    for (int i = 0; i < N; ++i) g[i] -= o.g[i];
    for (int i = 0; i < kPacked; ++i) h[i] -= o.h[i];
    return *this;
  }
  Hyper& operator*=(const Hyper& o) {
    *this = *this * o;
    return *this;
  }
  Hyper& operator/=(const Hyper& o) {
    *this = *this / o;
    return *this;
  }
  Hyper& operator+=(double a) {
    v += a;
    return *this;
  }
  Hyper& operator-=(double a) {
    v -= a;
    return *this;
  }
  Hyper& operator*=(double a) {
    v *= a;
    for (auto& x : g) x *= a;
    for (auto& x : h) x *= a;
    return *this;
  }

  friend Hyper operator+(Hyper a, const Hyper& b) { return a += b; }
  friend Hyper operator-(Hyper a, const Hyper& b) { return a -= b; }
  friend Hyper operator+(Hyper a, double b) { return a += b; }
  friend Hyper operator+(double b, Hyper a) { return a += b; }
  friend Hyper operator-(Hyper a, double b) { return a -= b; }
  friend Hyper operator-(double b, const Hyper& a) { return (-a) += b; }
  friend Hyper operator*(Hyper a, double b) { return a *= b; }
  friend Hyper operator*(double b, Hyper a) { return a *= b; }
  friend Hyper operator/(Hyper a, double b) { return a *= (1.0 / b); }
  friend Hyper operator-(Hyper a) { return a *= -1.0; }
  friend Hyper operator+(const Hyper& a) { return a; }

  friend Hyper operator*(const Hyper& a, const Hyper& b) {
    Hyper r(a.v * b.v);
    for (int i = 0; i < N; ++i) r.g[i] = a.v * b.g[i] + b.v * a.g[i];
    int k = 0;
    for (int i = 0; i < N; ++i)
      for (int j = 0; j <= i; ++j, ++k)
        r.h[k] = a.v * b.h[k] + b.v * a.h[k] + a.g[i] * b.g[j] + a.g[j] * b.g[i];
    return r;
  }
  /// f(a) given f, f', f'' at a.v (chain rule to second order).
  static Hyper chain(const Hyper& a, double f, double df, double d2f) {
    Hyper r(f);
    for (int i = 0; i < N; ++i) r.g[i] = df * a.g[i];
    int k = 0;
    for (int i = 0; i < N; ++i)
      for (int j = 0; j <= i; ++j, ++k) r.h[k] = df * a.h[k] + d2f * a.g[i] * a.g[j];
    return r;
  }
  friend Hyper operator/(const Hyper& a, const Hyper& b) {
    const double inv = 1.0 / b.v;
    return a * chain(b, inv, -inv * inv, 2.0 * inv * inv * inv);
  }
  friend Hyper operator/(double a, const Hyper& b) {
    const double inv = 1.0 / b.v;
    return chain(b, a * inv, -a * inv * inv, 2.0 * a * inv * inv * inv);
  }

  friend bool operator<(const Hyper& a, const Hyper& b) { return a.v < b.v; }
  friend bool operator>(const Hyper& a, const Hyper& b) { return a.v > b.v; }
  friend bool operator<=(const Hyper& a, const Hyper& b) { return a.v <= b.v; }
  friend bool operator>=(const Hyper& a, const Hyper& b) { return a.v >= b.v; }
  friend bool operator==(const Hyper& a, const Hyper& b) { return a.v == b.v; }
  friend bool operator!=(const Hyper& a, const Hyper& b) { return a.v != b.v; }
};

template <int N>
Hyper<N> sqrt(const Hyper<N>& a) {
  const double s = std::sqrt(a.v);
  return Hyper<N>::chain(a, s, 0.5 / s, -0.25 / (s * a.v));
}
template <int N>
Hyper<N> tanh(const Hyper<N>& a) {
  const double t = std::tanh(a.v);
  const double d = 1.0 - t * t;
  return Hyper<N>::chain(a, t, d, -2.0 * t * d);
}
template <int N>
Hyper<N> cos(const Hyper<N>& a) {
  return Hyper<N>::chain(a, std::cos(a.v), -std::sin(a.v), -std::cos(a.v));
}
template <int N>
Hyper<N> sin(const Hyper<N>& a) {
  return Hyper<N>::chain(a, std::sin(a.v), std::cos(a.v), -std::sin(a.v));
}

/// x * theta_k where theta_k is independent variable k at value 0: O(N) instead of a full product.
template <int N>
Hyper<N> times_variable(const Hyper<N>& x, int k) {
  Hyper<N> r(0.0);
  r.g[k] = x.v;
  for (int i = 0; i < N; ++i) r.h[Hyper<N>::packed(i, k)] = x.g[i];
  r.h[Hyper<N>::packed(k, k)] = 2.0 * x.g[k];
  return r;
}

/// Plain value of a scalar (double or Hyper).
inline double value_of(double x) { return x; }
template <int N>
double value_of(const Hyper<N>& x) {
  return x.v;
}

}  // namespace tfmb::beam

namespace Eigen {
template <int N>
struct NumTraits<tfmb::beam::Hyper<N>> : NumTraits<double> {
  using Real = tfmb::beam::Hyper<N>;
  using NonInteger = tfmb::beam::Hyper<N>;
  using Nested = tfmb::beam::Hyper<N>;
  using Literal = double;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = 1,
    AddCost = N + N * (N + 1) / 2,
    MulCost = 3 * N * (N + 1)
  };
};
template <int N, typename BinaryOp>
struct ScalarBinaryOpTraits<tfmb::beam::Hyper<N>, double, BinaryOp> {
  using ReturnType = tfmb::beam::Hyper<N>;
};
template <int N, typename BinaryOp>
struct ScalarBinaryOpTraits<double, tfmb::beam::Hyper<N>, BinaryOp> {
  using ReturnType = tfmb::beam::Hyper<N>;
};
}  // namespace Eigen
