#pragma once
// Text for people: lists in messages ("a, b, c") and numbers with a chosen number of significant
// digits. One definition each, so every message and file spells them the same way.
#include <string>
#include <vector>

namespace arcplan {

// joinText({"a", "b", "c"}, ", ") == "a, b, c"; an empty list gives "". Written here rather than
// taken from Boost (boost::algorithm::join) so that arcplan::common needs nothing beyond the
// standard library; C++17 has no join of its own.
std::string joinText(const std::vector<std::string>& parts, const std::string& separator);

// `value` with at most `significantDigits` significant digits, the shortest of fixed or scientific
// notation as std::ostream prints it ("0.1", "1e-07", "nan", "inf").
std::string formatNumber(double value, int significantDigits);

}  // namespace arcplan
