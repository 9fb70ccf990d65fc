#include "command_line.h"

#include <iostream>
#include <string>

#include "arcplan/common/error.h"
#include "cli_support.h"
#include "exit_codes.h"

namespace arcplan::apps {
namespace {

// "arcplan plan" for a usage error inside `plan`: the deepest subcommand the parser had reached.
std::string commandPath(const CLI::App& app) {
  std::string path = app.get_name().empty() ? "arcplan" : app.get_name();
  for (const CLI::App* command = &app; !command->get_subcommands().empty();) {
    command = command->get_subcommands().front();
    path += " " + command->get_name();
  }
  return path;
}

// CLI11's own messages do not name the command; point to its --help.
int reportParseError(const CLI::App& app, const std::string& message) {
  std::cerr << "arcplan: error: " << message << " (see '" << commandPath(app) << " --help')\n";
  return toInt(ExitCode::Usage);
}

}  // namespace

int runCommandLine(CLI::App& app, int argc, const char* const* argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);  // --help, --version
  } catch (const CLI::RuntimeError& e) {
    return e.get_exit_code();  // a command that ends with a code of the table (bench: interrupted)
  } catch (const CLI::ParseError& e) {
    return reportParseError(app, e.what());
  } catch (const UsageError& e) {
    std::cerr << "arcplan: error: " << e.what() << "\n";  // names the option already
    return toInt(ExitCode::Usage);
  } catch (const Error& e) {
    std::cerr << "arcplan: error: " << e.what() << "\n";
    return toInt(ExitCode::BadInput);
  } catch (const std::exception& e) {
    std::cerr << "arcplan: internal error: " << e.what() << "\n";
    return toInt(ExitCode::Internal);
  }
  return toInt(ExitCode::Success);
}

}  // namespace arcplan::apps
