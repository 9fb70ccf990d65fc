#pragma once
// Base64 (RFC 4648) of binary arrays for the report's JSON: meshes and pose frames travel as
// Float32/Uint32 arrays the page decodes with atob() into typed arrays. Hand-written (a dozen lines)
// because none of arcplan's Debian dependencies exports an encoder.
#include <cstddef>
#include <string>
#include <vector>

namespace arcplan::report::detail {

std::string base64(const unsigned char* bytes, std::size_t size);

template <typename T>
std::string base64Of(const std::vector<T>& values) {
  return base64(reinterpret_cast<const unsigned char*>(values.data()), values.size() * sizeof(T));
}

}  // namespace arcplan::report::detail
