#pragma once
// Runs a parsed command line and turns every way it can end into one line on stderr and an exit
// code of exit_codes.h (docs/cli.md): the error contract of the `arcplan` executable in one place.
#include <CLI/CLI.hpp>

namespace arcplan::apps {

// Parses argv with `app` (whose subcommands run from their callbacks) and returns the exit code:
// --help / --version 0; CLI11's parse errors and UsageError "arcplan: error: ..." and 2;
// arcplan::Error "arcplan: error: ..." and 1; CLI::RuntimeError its own code (bench: 130);
// any other exception "arcplan: internal error: ..." and 3.
int runCommandLine(CLI::App& app, int argc, const char* const* argv);

}  // namespace arcplan::apps
