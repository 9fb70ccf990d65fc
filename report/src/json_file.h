#pragma once
// A JSON file another arcplan command wrote (scene.json, campaign.json, diagnose_ranking.json, ...).
#include <filesystem>

#include <nlohmann/json.hpp>

namespace arcplan::report::detail {

// Throws arcplan::Error naming the file when it cannot be read or is not JSON.
nlohmann::json readJsonFile(const std::filesystem::path& file);

}  // namespace arcplan::report::detail
