#include "tfmb-heat/trace.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tfmb::heat {

Trace::Trace(std::vector<double> arc_length, std::vector<double> values, std::string name)
    : s_(std::move(arc_length)), values_(std::move(values)), name_(std::move(name)) {
  if (s_.empty()) throw std::invalid_argument(name_ + ": empty trace");
  if (s_.size() != values_.size()) {
    throw std::invalid_argument(name_ + ": " + std::to_string(s_.size()) + " arc lengths but " +
                                std::to_string(values_.size()) + " values");
  }
  for (std::size_t i = 0; i < s_.size(); ++i) {
    if (!std::isfinite(s_[i]) || !std::isfinite(values_[i])) {
      throw std::invalid_argument(name_ + ": non-finite entry at point " + std::to_string(i));
    }
    if (i > 0 && !(s_[i] > s_[i - 1])) {
      throw std::invalid_argument(name_ + ": arc length not strictly increasing at point " +
                                  std::to_string(i));
    }
  }
}

double Trace::min_value() const { return *std::min_element(values_.begin(), values_.end()); }

double Trace::at(double s, double tolerance) const {
  if (s < s_.front() - tolerance || s > s_.back() + tolerance) {
    throw std::invalid_argument(name_ + ": wall point at s = " + std::to_string(s) +
                                " m lies outside the trace [" + std::to_string(s_.front()) +
                                ", " + std::to_string(s_.back()) + "] m");
  }
  if (s <= s_.front()) return values_.front();
  if (s >= s_.back()) return values_.back();
  const auto it = std::upper_bound(s_.begin(), s_.end(), s);
  const auto i = static_cast<std::size_t>(it - s_.begin()) - 1;
  const double w = (s - s_[i]) / (s_[i + 1] - s_[i]);
  return (1.0 - w) * values_[i] + w * values_[i + 1];
}

}  // namespace tfmb::heat
