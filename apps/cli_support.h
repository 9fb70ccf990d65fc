#pragma once
// Small helpers shared by the subcommands: option parsing of vectors, JSON output files, and the
// exception for a wrong command line.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "arcplan/common/error.h"

namespace arcplan::apps {

// The command line itself is wrong (an option value out of range, options that exclude each
// other): main() prints the message and exits with ExitCode::Usage. The message names the option.
class UsageError : public Error {
public:
  using Error::Error;
};

// Writes `document` (pretty-printed) atomically; "-" writes to stdout.
void writeJson(const std::filesystem::path& file, const nlohmann::json& document);

// "q0,q1,...": exactly `count` finite numbers, else UsageError naming `option`.
std::vector<double> parseVector(const std::string& text, const std::string& option, std::size_t count);

// Throws UsageError "<option> must be a positive number (<unit>), got <value>" unless value > 0 and finite.
void requirePositive(double value, const std::string& option, const std::string& unit);

}  // namespace arcplan::apps
