// libFuzzer entry point; ARCPLAN_FUZZ_TARGET names the parser (see parser_targets.cpp).
#include <cstddef>
#include <cstdint>

#include "parser_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto& target = arcplan::fuzz::parserTarget(ARCPLAN_FUZZ_TARGET);
  arcplan::fuzz::runParserTarget(target, {reinterpret_cast<const char*>(data), size});
  return 0;
}
