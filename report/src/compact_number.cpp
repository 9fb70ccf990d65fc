#include "compact_number.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace arcplan::report::detail {

double withSignificantDigits(double value, int digits) {
  if (!std::isfinite(value) || value == 0.0) return value;
  char text[40];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return std::strtod(text, nullptr);
}

}  // namespace arcplan::report::detail
