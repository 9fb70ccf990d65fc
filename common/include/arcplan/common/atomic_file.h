#pragma once
// Output files are written to a temporary file next to the target and renamed into place only
// when complete, so an interrupted or failing command never leaves a half-written result.
// A target that exists and is not a regular file (/dev/null, /dev/stdout, a FIFO) is written in
// place: renaming onto it would replace the device itself (as root, /dev/null became a plain file).
// A symbolic link to a file is followed, so the link stays and the file it names is replaced.
#include <filesystem>
#include <fstream>
#include <string>

namespace arcplan {

class AtomicOutputFile {
public:
  explicit AtomicOutputFile(std::filesystem::path target);
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;
  ~AtomicOutputFile();  // removes the temporary file unless commit() succeeded

  std::ofstream& stream() { return stream_; }
  // Flushes, checks the stream and renames the temporary file onto the target. Throws arcplan::Error.
  void commit();

private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  std::ofstream stream_;
  bool inPlace_ = false;  // a device or pipe: no temporary, no rename
  bool committed_ = false;
};

// Convenience for small outputs (JSON, Markdown): the whole content at once.
void writeFileAtomically(const std::filesystem::path& target, const std::string& content);

}  // namespace arcplan
