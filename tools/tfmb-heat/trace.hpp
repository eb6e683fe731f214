#pragma once
// A quantity given along a wall as a function of arc length s (e.g. the flow's wall traces of
// temperature, heat transfer coefficient or adiabatic wall temperature), interpolated linearly.
#include <string>
#include <vector>

namespace tfmb::heat {

class Trace {
 public:
  Trace() = default;
  /// Throws std::invalid_argument unless sizes match, s is strictly increasing and values are
  /// finite. `name` is used in error messages (e.g. "wall 'upper_inner': h").
  Trace(std::vector<double> arc_length, std::vector<double> values, std::string name = "trace");

  bool empty() const { return s_.empty(); }
  const std::string& name() const { return name_; }
  double front_s() const { return s_.front(); }
  double back_s() const { return s_.back(); }
  double min_value() const;

  /// Value at s. Points within `tolerance` [m] outside [s_front, s_back] take the end value;
  /// points further out throw std::invalid_argument (the trace does not cover the wall).
  double at(double s, double tolerance) const;

 private:
  std::vector<double> s_;       // [m]
  std::vector<double> values_;
  std::string name_ = "trace";
};

}  // namespace tfmb::heat
