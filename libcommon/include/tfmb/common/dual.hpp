// First-order forward automatic differentiation with a fixed number of variables.
//
// A Dual<N> carries a value and its derivatives with respect to N independent variables. A
// kernel written once as a template on its scalar type, evaluated with Dual<N>, gives its exact
// Jacobian with respect to N inputs at the cost of about N + 1 evaluations, without hand
// derivatives (Griewank and Walther 2008, Evaluating Derivatives, ch. 3: the tangent mode).
// Branches (min, max, clipping) take the branch of the value, so the derivative is that of the
// active branch, as a hand derivative would be.
#pragma once

#include <array>
#include <cmath>

namespace tfmb {

template <int N>
struct Dual {
  double v = 0.0;
  std::array<double, N> d{};

  Dual() = default;
  Dual(double value) : v(value) {}  // NOLINT: a constant is a Dual with zero derivatives

  // Independent variable number `index` with value `value`.
  static Dual variable(int index, double value) {
    Dual x(value);
    x.d[index] = 1.0;
    return x;
  }

  Dual& operator+=(const Dual& o) {
    v += o.v;
    for (int i = 0; i < N; ++i)
      d[i] += o.d[i];
    return *this;
  }
  Dual& operator-=(const Dual& o) {
    v -= o.v;
    for (int i = 0; i < N; ++i)
      d[i] -= o.d[i];
    return *this;
  }
  Dual& operator*=(const Dual& o) {
    for (int i = 0; i < N; ++i)
      d[i] = d[i] * o.v + v * o.d[i];
    v *= o.v;
    return *this;
  }
  Dual& operator/=(const Dual& o) {
    const double inv = 1.0 / o.v;
    for (int i = 0; i < N; ++i)
      d[i] = (d[i] - v * inv * o.d[i]) * inv;
    v *= inv;
    return *this;
  }
  Dual& operator*=(double a) {
    v *= a;
    for (auto& x : d)
      x *= a;
    return *this;
  }

  friend Dual operator+(Dual a, const Dual& b) { return a += b; }
  friend Dual operator-(Dual a, const Dual& b) { return a -= b; }
  friend Dual operator*(Dual a, const Dual& b) { return a *= b; }
  friend Dual operator/(Dual a, const Dual& b) { return a /= b; }
  friend Dual operator+(Dual a, double b) {
    a.v += b;
    return a;
  }
  friend Dual operator+(double b, Dual a) { return a + b; }
  friend Dual operator-(Dual a, double b) {
    a.v -= b;
    return a;
  }
  friend Dual operator-(double b, const Dual& a) { return -a + b; }
  friend Dual operator*(Dual a, double b) { return a *= b; }
  friend Dual operator*(double b, Dual a) { return a *= b; }
  friend Dual operator/(Dual a, double b) { return a *= (1.0 / b); }
  friend Dual operator/(double b, const Dual& a) { return Dual(b) / a; }
  friend Dual operator-(Dual a) { return a *= -1.0; }

  // comparisons look at the value only
  friend bool operator<(const Dual& a, const Dual& b) { return a.v < b.v; }
  friend bool operator>(const Dual& a, const Dual& b) { return a.v > b.v; }
  friend bool operator<=(const Dual& a, const Dual& b) { return a.v <= b.v; }
  friend bool operator>=(const Dual& a, const Dual& b) { return a.v >= b.v; }
  friend bool operator<(const Dual& a, double b) { return a.v < b; }
  friend bool operator>(const Dual& a, double b) { return a.v > b; }
  friend bool operator<=(const Dual& a, double b) { return a.v <= b; }
  friend bool operator>=(const Dual& a, double b) { return a.v >= b; }
  friend bool operator<(double a, const Dual& b) { return a < b.v; }
  friend bool operator>(double a, const Dual& b) { return a > b.v; }
  friend bool operator<=(double a, const Dual& b) { return a <= b.v; }
  friend bool operator>=(double a, const Dual& b) { return a >= b.v; }
};

// f(a) with f'(a) given: the chain rule for the elementary functions below
template <int N>
Dual<N> chain(const Dual<N>& a, double value, double derivative) {
  Dual<N> r(value);
  for (int i = 0; i < N; ++i)
    r.d[i] = derivative * a.d[i];
  return r;
}

template <int N>
Dual<N> sqrt(const Dual<N>& a) {
  const double s = std::sqrt(a.v);
  return chain(a, s, 0.5 / s);
}
template <int N>
Dual<N> cbrt(const Dual<N>& a) {
  const double c = std::cbrt(a.v);
  return chain(a, c, 1.0 / (3.0 * c * c));
}
template <int N>
Dual<N> exp(const Dual<N>& a) {
  const double e = std::exp(a.v);
  return chain(a, e, e);
}
template <int N>
Dual<N> log(const Dual<N>& a) {
  return chain(a, std::log(a.v), 1.0 / a.v);
}
template <int N>
Dual<N> pow(const Dual<N>& a, double p) {
  const double value = std::pow(a.v, p);
  return chain(a, value, p * std::pow(a.v, p - 1.0));
}
template <int N>
Dual<N> abs(const Dual<N>& a) {
  return a.v < 0.0 ? -a : a;
}
template <int N>
Dual<N> min(const Dual<N>& a, const Dual<N>& b) {
  return b.v < a.v ? b : a;
}
template <int N>
Dual<N> max(const Dual<N>& a, const Dual<N>& b) {
  return a.v < b.v ? b : a;
}

// The value of a plain number or of a Dual, for code templated on its scalar.
inline double value_of(double x) {
  return x;
}
template <int N>
double value_of(const Dual<N>& x) {
  return x.v;
}

}  // namespace tfmb
