// Numbers in messages, logs and provenance text: one formatter for every tool. No physics.
#pragma once

#include <string>

namespace tfmb::text {

// `value` with `significant_digits` significant digits in the stream's general notation
// (1.5, 0.000125, 2.44e+05): what the tools print in messages and summaries.
std::string format_number(double value, int significant_digits = 6);

}  // namespace tfmb::text
