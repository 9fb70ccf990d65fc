#pragma once
// Decodes the report's base64 arrays in tests, by a table lookup written here (RFC 4648), so what
// the report encodes is checked against a second implementation rather than against itself.
#include <cstring>
#include <string>
#include <vector>

namespace arcplan::testing {

// The bytes of standard base64 text ('=' padding ends it).
inline std::vector<unsigned char> decodeBase64(const std::string& text) {
  const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> bytes;
  unsigned buffer = 0;
  int bits = 0;
  for (const char c : text) {
    if (c == '=') break;
    buffer = (buffer << 6) | static_cast<unsigned>(alphabet.find(c));
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      bytes.push_back(static_cast<unsigned char>((buffer >> bits) & 0xFF));
    }
  }
  return bytes;
}

// The values of base64 text holding an array of T in this machine's (little-endian) byte order,
// as the page's Float32Array / Uint32Array read it.
template <typename T>
std::vector<T> decodeBase64Array(const std::string& text) {
  const auto bytes = decodeBase64(text);
  std::vector<T> values(bytes.size() / sizeof(T));
  std::memcpy(values.data(), bytes.data(), values.size() * sizeof(T));
  return values;
}

}  // namespace arcplan::testing
