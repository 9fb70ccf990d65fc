// arcplan: planning, collision checking, time scaling, benchmarks and model validation for the UR10e.
#include <iostream>

#include <CLI/CLI.hpp>

#include "arcplan/common/error.h"
#include "commands.h"

int main(int argc, char** argv) {
  CLI::App app{"arcplan — arc obstacle-avoidance planning, FCL collision checking and TCP-speed time scaling "
               "for the UR10e, OMPL benchmarks, and robot models checked against measurements"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string(ARCPLAN_VERSION));
  arcplan::apps::registerRobotCommand(app);
  arcplan::apps::registerPlanCommand(app);
  arcplan::apps::registerScaleCommand(app);
  arcplan::apps::registerModelCommand(app);
  arcplan::apps::registerBenchCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const arcplan::Error& e) {
    std::cerr << "arcplan: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "arcplan: internal error: " << e.what() << "\n";
    return 3;
  }
  return 0;
}
