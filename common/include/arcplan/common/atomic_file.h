#pragma once
// Output files are written to a temporary file next to the target and renamed into place only
// when complete, so an interrupted or failing command never leaves a half-written result.
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
  bool committed_ = false;
};

// Convenience for small outputs (JSON, Markdown): the whole content at once.
void writeFileAtomically(const std::filesystem::path& target, const std::string& content);

}  // namespace arcplan
