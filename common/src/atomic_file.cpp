#include "arcplan/common/atomic_file.h"

#include <cerrno>
#include <cstring>
#include <system_error>
#include <unistd.h>

#include "arcplan/common/error.h"

namespace arcplan {

AtomicOutputFile::AtomicOutputFile(std::filesystem::path target) : target_(std::move(target)) {
  std::error_code ec;
  const auto status = std::filesystem::status(target_, ec);  // follows symbolic links
  if (!ec && std::filesystem::is_directory(status)) {
    throw Error("cannot write " + target_.string() + ": it is a directory, expected a file name");
  }
  if (!ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    inPlace_ = true;
    stream_.open(target_, std::ios::out | std::ios::binary);
    if (!stream_) throw Error("cannot write " + target_.string() + ": " + std::strerror(errno));
    return;
  }
  if (std::filesystem::is_symlink(std::filesystem::symlink_status(target_, ec))) {
    const auto resolved = std::filesystem::canonical(target_, ec);
    if (!ec) target_ = resolved;
  }
  if (target_.has_parent_path()) {
    std::filesystem::create_directories(target_.parent_path(), ec);
    if (ec) throw Error("cannot create directory " + target_.parent_path().string() + ": " + ec.message());
  }
  // pid in the name: concurrent writers (benchmark shards) never share a temporary file.
  temporary_ = target_;
  temporary_ += ".tmp." + std::to_string(::getpid());
  stream_.open(temporary_, std::ios::out | std::ios::trunc | std::ios::binary);
  if (!stream_) {
    throw Error("cannot write " + target_.string() + " (temporary " + temporary_.string() +
                "): " + std::strerror(errno));
  }
}

AtomicOutputFile::~AtomicOutputFile() {
  if (!committed_ && !inPlace_) {
    stream_.close();
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
  }
}

void AtomicOutputFile::commit() {
  // errno still holds the reason of the write that failed (a full disk, a file size limit).
  stream_.flush();
  if (!stream_) throw Error("writing " + target_.string() + " failed: " + std::strerror(errno));
  stream_.close();
  if (stream_.fail()) throw Error("writing " + target_.string() + " failed on close: " + std::strerror(errno));
  if (inPlace_) {
    committed_ = true;
    return;
  }
  std::error_code ec;
  std::filesystem::rename(temporary_, target_, ec);
  if (ec) throw Error("cannot move " + temporary_.string() + " to " + target_.string() + ": " + ec.message());
  committed_ = true;
}

void writeFileAtomically(const std::filesystem::path& target, const std::string& content) {
  AtomicOutputFile file(target);
  file.stream() << content;
  file.commit();
}

}  // namespace arcplan
