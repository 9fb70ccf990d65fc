#pragma once
// Small helpers shared by the subcommands: option parsing of vectors, JSON output files, and the
// exception for a wrong command line.
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "arcplan/common/error.h"
#include "arcplan/robot/robot_source.h"

namespace arcplan::apps {

// The command line itself is wrong (an option value out of range, options that exclude each
// other): main() prints the message and exits with ExitCode::Usage. The message names the option.
class UsageError : public Error {
public:
  using Error::Error;
};

// Writes `document` (pretty-printed) atomically; "-" writes to stdout (through C stdio, so a DropStdout
// in force does not swallow it).
void writeJson(const std::filesystem::path& file, const nlohmann::json& document);

// docs/cli.md: with `--json -` the JSON document is all that goes to stdout, so while one of these is
// alive with drop = true the text for people written to std::cout (tables, "plots written to ...") is
// dropped. Construct it at the start of a command that takes --json.
class DropStdout {
public:
  explicit DropStdout(bool drop) : saved_(drop ? std::cout.rdbuf(nullptr) : nullptr) {}
  ~DropStdout() {
    if (saved_) std::cout.rdbuf(saved_);  // also clears the badbit a null buffer set
  }
  DropStdout(const DropStdout&) = delete;
  DropStdout& operator=(const DropStdout&) = delete;

private:
  std::streambuf* saved_;
};

// "q0,q1,...": exactly `count` finite numbers, else UsageError naming `option`.
std::vector<double> parseVector(const std::string& text, const std::string& option, std::size_t count);

// Throws UsageError "<option> must be a positive number (<unit>), got <value>" unless value > 0 and finite.
void requirePositive(double value, const std::string& option, const std::string& unit);

// `-j,--workers N` of the commands that run a campaign (bench, bench baseline check): worker processes
// running jobs in parallel, all cores unless given (`workers` is set to that default here).
void addWorkersOption(CLI::App& command, unsigned& workers);
// Throws UsageError "--workers must be at least 1" for 0.
void requireWorkers(unsigned workers);

// The robot options of every command that takes a robot (robot fk|ik|check, scale): --urdf F, or
// --ur-type T [--description DIR] [--kinematics F] (docs/cli.md), and the TCP: --tip LINK, --tcp-offset.
struct RobotSourceOptions {
  std::string urdf;
  std::string urType;
  std::string description;
  std::string kinematics;
  std::string tip = "tool0";
  std::string tcpOffset;
  bool given() const { return !urdf.empty() || !urType.empty() || tip != "tool0" || !tcpOffset.empty(); }
};
void addRobotSourceOptions(CLI::App& command, RobotSourceOptions& options, const std::string& urdfHelp);

// `--collision prefilter|exact-only`, applied when parsed, before the command builds any collision model.
void addCollisionModeOption(CLI::App& command);

// What those options name; nothing given: arcplan's built-in UR10e. UsageError for --description or
// --kinematics without --ur-type or a malformed --tcp-offset; Error for a file or folder that does not exist.
robot::RobotSource robotSourceFrom(const RobotSourceOptions& options);

}  // namespace arcplan::apps
