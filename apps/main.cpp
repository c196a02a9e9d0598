// The graspsynth command: a thin front end over the libraries. Each subcommand parses its
// options, calls the libraries and prints what they report.

#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>

#include "apps/analyze_command.hpp"
#include "apps/demos_command.hpp"
#include "apps/generalize_command.hpp"
#include "apps/kinematics_commands.hpp"
#include "apps/run_command.hpp"
#include "apps/select_command.hpp"
#include "apps/simulate_command.hpp"
#include "apps/synthesize_command.hpp"
#include "apps/teleop_command.hpp"
#include "apps/view_command.hpp"
#include "collision/library_info.hpp"
#include "simulation/library_info.hpp"
#include "solver/library_info.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "graspsynth: demonstration-seeded grasp synthesis for a PA-10 arm with a Gifu Hand III.\n"
      "Run 'graspsynth <command> --help' for the options of one command."};
  app.require_subcommand(1);
  int exit_code = 0;

  graspsynth::apps::AddRunCommand(app, &exit_code);
  graspsynth::apps::AddKinematicsCommands(app, &exit_code);
  graspsynth::apps::AddAnalyzeCommand(app, &exit_code);
  graspsynth::apps::AddDemosCommand(app, &exit_code);
  graspsynth::apps::AddSimulateCommand(app, &exit_code);
  graspsynth::apps::AddSynthesizeCommand(app, &exit_code);
  graspsynth::apps::AddGeneralizeCommand(app, &exit_code);
  graspsynth::apps::AddSelectCommand(app, &exit_code);
  graspsynth::apps::AddViewCommand(app, &exit_code);
  graspsynth::apps::AddTeleopCommands(app, &exit_code);

  auto* version = app.add_subcommand("version", "Print the versions of the linked libraries");
  version->callback([] {
    std::cout << "graspsynth 0.1.0\n"
              << "  " << graspsynth::CollisionLibraryInfo() << "\n"
              << "  " << graspsynth::SimulationLibraryInfo() << "\n"
              << "  " << graspsynth::SolverLibraryInfo() << "\n";
  });

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "graspsynth: error: " << e.what() << "\n";
    return 2;
  }
  return exit_code;
}
