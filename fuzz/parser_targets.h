#pragma once
// One entry point per parser of arcplan, shared by the libFuzzer executables (scripts/fuzz) and by
// the mutation regression test that runs in every CTest run (tests/fuzz). A target feeds the bytes
// to its parser and returns normally for a parse or an arcplan::Error; anything else — another
// exception type, a crash, a sanitizer report — is a bug the fuzzer found.
#include <string>
#include <string_view>
#include <vector>

namespace arcplan::fuzz {

struct ParserTarget {
  std::string name;        // "scene", "urdf", ...
  std::string fileSuffix;  // file-based parsers read a temporary file with this suffix
  void (*parse)(const std::string& input);
};

const std::vector<ParserTarget>& parserTargets();
const ParserTarget& parserTarget(const std::string& name);  // throws std::out_of_range if unknown

// Runs one input through a target; true if it parsed, false if it was rejected with arcplan::Error.
bool runParserTarget(const ParserTarget& target, std::string_view input);

}  // namespace arcplan::fuzz
