// The graspsynth command: a thin front end over the libraries. Each subcommand parses its
// options, calls the libraries and prints what they report.

#include <CLI/CLI.hpp>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <memory>
#include <string>

#include "apps/analyze_command.hpp"
#include "apps/cli_helpers.hpp"
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
#ifdef GRASPSYNTH_HAS_MPI
#include "common/mpi_job_runner.hpp"
#endif
#include "simulation/library_info.hpp"
#include "solver/library_info.hpp"

namespace {

// The MPI job this process belongs to, if any (README, "Running at scale"): its rank and size,
// and how to end every rank after an error on this one.
#ifdef GRASPSYNTH_HAS_MPI
using Mpi = graspsynth::MpiSession;
#else
struct Mpi {
  Mpi(int*, char***) {}
  int rank() const { return 0; }
  int size() const { return 1; }
  std::unique_ptr<graspsynth::JobRunner> MakeRunner() const {
    return std::make_unique<graspsynth::LocalJobRunner>();
  }
  [[noreturn]] void AbortAll(int code) const { std::exit(code); }
};
#endif

constexpr const char* kEmptyValue = "an empty value (leave the option out to take its default)";

// Refuses an empty value for every option that takes one, in `app` and its subcommands: an
// empty --object or --at would otherwise mean "not given" without a word (README, "Commands");
// leaving the option out is how its default is asked for.
void RefuseEmptyValues(CLI::App* app) {
  for (CLI::Option* option : app->get_options()) {
    if (option->get_type_size() == 0) continue;  // a flag takes no value
    option->check(CLI::Validator(
        [](const std::string& value) {
          return value.empty() ? std::string(kEmptyValue) : std::string();
        },
        "", "non-empty"));
  }
  for (CLI::App* command : app->get_subcommands({})) RefuseEmptyValues(command);
}

}  // namespace

int main(int argc, char** argv) {
  const Mpi mpi(&argc, &argv);
  graspsynth::apps::SetProcessRunner(mpi.MakeRunner());
  // the other ranks compute; rank 0 alone prints and writes.
  if (mpi.rank() > 0 && !std::freopen("/dev/null", "w", stdout)) mpi.AbortAll(2);
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

  RefuseEmptyValues(&app);
  // CLI11 takes "--object=" as the option without its value and then the next argument in its
  // place ("--object= --out X" would lose --out): refused here, before it parses.
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--") break;
    if (arg.size() > 3 && arg.rfind("--", 0) == 0 && arg.back() == '=') {
      std::cerr << arg.substr(0, arg.size() - 1) << ": " << kEmptyValue << "\n";
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    // a stage's error reaches every rank of an MPI job: rank 0 reports it.
    if (dynamic_cast<const graspsynth::StageFailedElsewhere*>(&e)) return 2;
    std::cerr << "graspsynth: error: "
              << (mpi.rank() > 0 ? "rank " + std::to_string(mpi.rank()) + ": " : std::string())
              << e.what() << "\n";
    // every rank has a stage's error and ends by itself. An error that rank 0 meets, or that
    // another rank meets alone (outside the stages), ends the whole MPI job: the other ranks
    // would wait for it.
    if (mpi.size() > 1 && !dynamic_cast<const graspsynth::StageFailedEverywhere*>(&e)) {
      mpi.AbortAll(2);
    }
    return 2;
  }
  return exit_code;
}
