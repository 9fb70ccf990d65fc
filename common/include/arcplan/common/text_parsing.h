#pragma once
// Strict number parsing shared by every reader (CSV logs, path files, command-line vectors): a
// field is a number only if the whole field is one; anything else is reported, never guessed.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace arcplan {

// The whole of `text` (surrounding blanks allowed) as a double; nullopt for empty text, trailing
// garbage or out-of-range values. "nan"/"inf" parse (callers decide whether they are allowed).
std::optional<double> parseDouble(std::string_view text);

// Splits on `separator`; with separator ' ' runs of blanks/tabs count as one separator.
std::vector<std::string_view> splitFields(std::string_view line, char separator);

std::string_view trim(std::string_view text);

// "0.1,0.2,0.3" -> {0.1, 0.2, 0.3}. Throws arcplan::Error naming `what` if a value is not a
// finite number or if expectedCount > 0 and the count differs.
std::vector<double> parseNumberList(std::string_view text, const std::string& what, std::size_t expectedCount = 0);

}  // namespace arcplan
