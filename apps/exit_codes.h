#pragma once
// The exit codes of the `arcplan` executable: one table for main(), the commands, the README and
// docs/cli.md (which explains them for users). Scripts rely on these numbers; do not renumber.
#include <array>

namespace arcplan::apps {

enum class ExitCode : int {
  Success = 0,
  BadInput = 1,       // a file or value arcplan cannot use, or a request it cannot carry out
  Usage = 2,          // the command line itself is wrong (as most Unix tools)
  Internal = 3,       // a bug: an exception that is not an arcplan::Error
  Interrupted = 130,  // Ctrl-C / SIGTERM (128 + SIGINT, as shells report it)
};

struct ExitCodeDescription {
  ExitCode code;
  const char* meaning;
};

inline constexpr std::array<ExitCodeDescription, 5> kExitCodes{{
    {ExitCode::Success, "success"},
    {ExitCode::BadInput, "bad input: a file or value arcplan cannot use, or a request it cannot carry out"},
    {ExitCode::Usage, "usage error: unknown command or option, missing or malformed option value"},
    {ExitCode::Internal, "internal error"},
    {ExitCode::Interrupted, "interrupted; run the same command again to resume"},
}};

constexpr int toInt(ExitCode code) { return static_cast<int>(code); }

}  // namespace arcplan::apps
