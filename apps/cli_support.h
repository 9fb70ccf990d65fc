#pragma once
// Small helpers shared by the subcommands: option parsing of vectors, JSON output files.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace arcplan::apps {

// Writes `document` (pretty-printed) atomically; "-" writes to stdout.
void writeJson(const std::filesystem::path& file, const nlohmann::json& document);

// "q0,q1,...": exactly `count` finite numbers, else arcplan::Error naming `option`.
std::vector<double> parseVector(const std::string& text, const std::string& option, std::size_t count);

}  // namespace arcplan::apps
