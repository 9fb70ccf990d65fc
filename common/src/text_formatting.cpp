#include "arcplan/common/text_formatting.h"

#include <iomanip>
#include <sstream>

namespace arcplan {

std::string joinText(const std::vector<std::string>& parts, const std::string& separator) {
  std::string text;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (i > 0) text += separator;
    text += parts[i];
  }
  return text;
}

std::string formatNumber(double value, int significantDigits) {
  std::ostringstream text;
  text << std::setprecision(significantDigits) << value;
  return text.str();
}

}  // namespace arcplan
