#include "tfmb/common/text.hpp"

#include <sstream>

namespace tfmb::text {

std::string format_number(double value, int significant_digits) {
  std::ostringstream out;
  out.precision(significant_digits);
  out << value;
  return out.str();
}

}  // namespace tfmb::text
