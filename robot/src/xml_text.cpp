#include "xml_text.h"

#include <algorithm>
#include <sstream>

#include "arcplan/common/error.h"

namespace arcplan::robot::detail {
namespace {

// Offset of the first byte that does not belong to a well-formed UTF-8 sequence (RFC 3629: no
// overlong forms, no surrogates, nothing above U+10FFFF), or of a NUL byte; npos if there is none.
// Written here because TinyXML 2.6 trusts a lead byte and skips the bytes it announces, so a
// sequence cut short at the end of the text walks past the terminating NUL (a heap over-read found
// by fuzzing); the check must run before any TinyXML call, and Debian 12 ships no maintained C++
// UTF-8 validator among arcplan's dependencies (std::wstring_convert is deprecated).
std::size_t firstInvalidUtf8Byte(const std::string& text) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  std::size_t i = 0;
  while (i < text.size()) {
    const unsigned char lead = byte(i);
    if (lead == 0) return i;
    if (lead < 0x80) {
      ++i;
      continue;
    }
    std::size_t continuationCount = 0;
    unsigned char secondMin = 0x80, secondMax = 0xBF;
    if (lead >= 0xC2 && lead <= 0xDF) {
      continuationCount = 1;
    } else if (lead >= 0xE0 && lead <= 0xEF) {
      continuationCount = 2;
      if (lead == 0xE0) secondMin = 0xA0;  // overlong
      if (lead == 0xED) secondMax = 0x9F;  // surrogates
    } else if (lead >= 0xF0 && lead <= 0xF4) {
      continuationCount = 3;
      if (lead == 0xF0) secondMin = 0x90;  // overlong
      if (lead == 0xF4) secondMax = 0x8F;  // above U+10FFFF
    } else {
      return i;
    }
    for (std::size_t k = 1; k <= continuationCount; ++k) {
      if (i + k >= text.size()) return i;
      const unsigned char next = byte(i + k);
      const unsigned char low = k == 1 ? secondMin : 0x80, high = k == 1 ? secondMax : 0xBF;
      if (next < low || next > high) return i;
    }
    i += continuationCount + 1;
  }
  return std::string::npos;
}

}  // namespace

void parseXml(const std::string& text, const std::string& sourceName, TiXmlDocument& document) {
  const std::size_t invalid = firstInvalidUtf8Byte(text);
  if (invalid != std::string::npos) {
    const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(invalid), '\n');
    std::ostringstream message;
    message << sourceName << ":" << line << ": expected UTF-8 text, found byte 0x" << std::hex
            << static_cast<int>(static_cast<unsigned char>(text[invalid])) << std::dec << " at offset " << invalid
            << (text[invalid] == '\0' ? " (a NUL byte)" : " (not a well-formed UTF-8 sequence)");
    throw Error(message.str());
  }
  document.Parse(text.c_str());
  if (document.Error()) {
    std::ostringstream message;
    message << sourceName << ":" << document.ErrorRow() << ":" << document.ErrorCol()
            << ": malformed XML: " << document.ErrorDesc();
    throw Error(message.str());
  }
}

}  // namespace arcplan::robot::detail
