// Output files of every command go through AtomicOutputFile: regular files are replaced by a
// rename, devices and pipes are written in place (a rename onto /dev/null as root replaces the
// device with a plain file), and a symbolic link keeps pointing at the file it names.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "arcplan/common/atomic_file.h"
#include "arcplan/common/error.h"

namespace {

namespace fs = std::filesystem;

class OutputFiles : public testing::Test {
protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("arcplan-output-files-" + std::to_string(::getpid()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }

  static std::string read(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  std::size_t entriesInFolder() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(folder_), fs::directory_iterator()));
  }

  fs::path folder_;
};

// A pipe stands for every target that is not a regular file (/dev/null, /dev/stdout): testing on
// /dev/null itself would, if the protection broke, turn the machine's /dev/null into a plain file.
TEST_F(OutputFiles, APipeStaysAPipeAndItsReaderGetsTheWholeText) {
  const fs::path pipe = folder_ / "results.fifo";
  ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
  const std::string text(100000, 'x');  // larger than a pipe buffer: the writer must stream, not rename
  std::string received;
  // Non-blocking, with a deadline: a writer that renames a file onto the pipe instead of writing
  // into it never appears, and the test fails instead of hanging.
  std::thread reader([&] {
    const int fd = ::open(pipe.c_str(), O_RDONLY | O_NONBLOCK);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    bool writerSeen = false;
    char buffer[4096];
    while (fd >= 0 && std::chrono::steady_clock::now() < deadline) {
      const ssize_t count = ::read(fd, buffer, sizeof buffer);
      if (count > 0) {
        received.append(buffer, static_cast<std::size_t>(count));
        writerSeen = true;
      } else if (count == 0 && writerSeen) {
        break;  // the writer closed its end
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
    }
    if (fd >= 0) ::close(fd);
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));  // the reader opens first, as a shell's would
  arcplan::writeFileAtomically(pipe, text);
  reader.join();

  EXPECT_EQ(received.size(), text.size());
  EXPECT_EQ(received, text);
  EXPECT_TRUE(fs::is_fifo(fs::symlink_status(pipe)));
  EXPECT_EQ(entriesInFolder(), 1u) << "a temporary file was left next to the pipe";
}

TEST_F(OutputFiles, ASymbolicLinkKeepsPointingAtTheReplacedFile) {
  const fs::path file = folder_ / "ranking.md";
  const fs::path link = folder_ / "latest.md";
  { std::ofstream(file) << "old"; }
  fs::create_symlink(file.filename(), link);

  arcplan::writeFileAtomically(link, "new");

  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(link)));
  EXPECT_EQ(read(file), "new");
  EXPECT_EQ(entriesInFolder(), 2u);
}

TEST_F(OutputFiles, AFolderAsTargetIsAClearError) {
  try {
    arcplan::writeFileAtomically(folder_, "text");
    FAIL() << "writing onto a folder did not fail";
  } catch (const arcplan::Error& error) {
    EXPECT_NE(std::string(error.what()).find("is a directory"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find(folder_.string()), std::string::npos) << error.what();
  }
  EXPECT_TRUE(fs::is_directory(folder_));
}

TEST_F(OutputFiles, AFailedWriteLeavesTheOldFileAndNoTemporary) {
  const fs::path file = folder_ / "old.json";
  { std::ofstream(file) << "{}"; }
  {
    arcplan::AtomicOutputFile output(file);
    output.stream() << "{\"half\":";
  }  // destroyed without commit, as when a command fails midway
  EXPECT_EQ(read(file), "{}");
  EXPECT_EQ(entriesInFolder(), 1u);
}

}  // namespace
