#pragma once
// Internal to arcplan::collision: what a file holds, as a cache key. The per-process caches of parsed
// descriptions (moveit_reading.cpp) and of mesh parts (mesh_part_cache.cpp) know a file by its content,
// not its path and modification time: a file rewritten in place within the same second (timestamps
// of one-second resolution, scripts that write and read back at once) must not be served stale.
#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <string_view>
#include <utility>

namespace arcplan::collision::detail {

// (hash, size) of the file's bytes; an unreadable file gives (hash of nothing, 0), and whoever parses it
// then says why. Read in one block: the MBM UR5's 13 collision meshes (4.8 MB) take ~1 ms so, ~40 ms
// through istreambuf_iterator.
inline std::pair<std::size_t, std::size_t> fileContentKey(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary | std::ios::ate);
  std::string bytes(static_cast<std::size_t>(std::max<std::streamoff>(0, in.tellg())), '\0');
  in.seekg(0);
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  return {std::hash<std::string_view>{}(bytes), bytes.size()};
}

}  // namespace arcplan::collision::detail
