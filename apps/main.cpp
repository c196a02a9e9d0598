// The graspsynth command: a thin front end over the libraries. Each subcommand parses its
// options, calls the libraries and prints what they report.

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "apps/analyze_command.hpp"
#include "apps/cli_helpers.hpp"
#include "apps/demos_command.hpp"
#include "apps/generalize_command.hpp"
#include "apps/help_formatter.hpp"
#include "apps/kinematics_commands.hpp"
#include "apps/mujoco_command.hpp"
#include "apps/run_command.hpp"
#include "apps/select_command.hpp"
#include "apps/simulate_command.hpp"
#include "apps/synthesize_command.hpp"
#include "apps/teleop_command.hpp"
#include "apps/view_command.hpp"
#include "collision/library_info.hpp"
#include "request/option.hpp"
#ifdef GRASPSYNTH_HAS_MPI
#include "common/mpi_job_runner.hpp"
#endif
#include "simulation/library_info.hpp"
#include "simulation_mujoco/mujoco_world.hpp"
#include "solver/library_info.hpp"

namespace {

// The MPI job this process belongs to, if any (docs/scale-out.md): its rank and size,
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

constexpr const char* kVersion = "graspsynth 0.1.0";

constexpr const char* kEmptyValue = "an empty value (leave the option out to take its default)";

// Refuses an empty value for every option that takes one, in `app` and its subcommands: an
// empty --object or --at would otherwise mean "not given" without a word (docs/commands.md);
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

// The subcommand the command line chose last (`app` when none).
CLI::App* ChosenCommand(CLI::App* app) {
  const std::vector<CLI::App*> chosen = app->get_subcommands();
  return chosen.empty() ? app : ChosenCommand(chosen.front());
}

// The flags of `command`, as the command line spells them ("--seed").
std::vector<std::string> FlagNames(const CLI::App* command) {
  std::vector<std::string> names;
  for (const CLI::Option* option : command->get_options()) {
    for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
  }
  return names;
}

// The names of the commands below `app`.
std::vector<std::string> CommandNames(const CLI::App* app) {
  std::vector<std::string> names;
  for (const CLI::App* command : app->get_subcommands({})) names.push_back(command->get_name());
  return names;
}

// The exit status of a command line that CLI11 refused or answered: 0 for --help and --version
// (printed), 2 for every refusal (README.md, "Commands": bad input), with the nearest flag for
// one that is misspelt.
int ParseErrorExit(CLI::App& app, const CLI::ParseError& e, int argc, char** argv) {
  const int code = app.exit(e);  // prints the help, the version or the error
  if (code == 0) return 0;
  const CLI::App* command = ChosenCommand(&app);
  const std::vector<std::string> flags = FlagNames(command);
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "--") break;
    if (arg.rfind("--", 0) != 0) continue;
    arg = arg.substr(0, arg.find('='));
    if (std::find(flags.begin(), flags.end(), arg) != flags.end()) continue;
    const std::string nearest = graspsynth::request::NearestName(flags, arg);
    if (!nearest.empty()) std::cerr << arg << ": did you mean " << nearest << "?\n";
  }
  return 2;
}

// Refuses a first argument that names no command, with the nearest one; true when it did.
bool RefuseUnknownCommand(const CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-' || argv[1][0] == '\0') return false;
  const std::string name = argv[1];
  const std::vector<std::string> names = CommandNames(&app);
  if (std::find(names.begin(), names.end(), name) != names.end()) return false;
  std::cerr << "graspsynth: '" << name << "' is not a command";
  const std::string nearest = graspsynth::request::NearestName(names, name);
  if (!nearest.empty()) std::cerr << " (did you mean '" << nearest << "'?)";
  std::cerr << "; 'graspsynth --help' lists the commands\n";
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  const Mpi mpi(&argc, &argv);
  graspsynth::apps::SetProcessRunner(mpi.MakeRunner());
  // the other ranks compute; rank 0 alone prints and writes.
  if (mpi.rank() > 0 && !std::freopen("/dev/null", "w", stdout)) mpi.AbortAll(2);
  CLI::App app{
      "graspsynth: demonstration-seeded grasp synthesis for a PA-10 arm with a Gifu Hand III.\n"
      "Run 'graspsynth COMMAND --help' for what a command does, an example and its options.",
      "graspsynth"};
  graspsynth::apps::UseHelpFormatter(&app);  // before the commands: they take it from here
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string(kVersion), "Print the version and exit");
  int exit_code = 0;

  graspsynth::apps::AddRunCommand(app, &exit_code);
  graspsynth::apps::AddKinematicsCommands(app, &exit_code);
  graspsynth::apps::AddAnalyzeCommand(app, &exit_code);
  graspsynth::apps::AddDemosCommand(app, &exit_code);
  graspsynth::apps::AddSimulateCommand(app, &exit_code);
  graspsynth::apps::AddExportMjcfCommand(app, &exit_code);
  graspsynth::apps::AddSynthesizeCommand(app, &exit_code);
  graspsynth::apps::AddGeneralizeCommand(app, &exit_code);
  graspsynth::apps::AddSelectCommand(app, &exit_code);
  graspsynth::apps::AddViewCommand(app, &exit_code);
  graspsynth::apps::AddTeleopCommands(app, &exit_code);

  auto* version = app.add_subcommand("version", "Print the versions of the linked libraries");
  version->callback([] {
    std::cout << kVersion << "\n"
              << "  " << graspsynth::CollisionLibraryInfo() << "\n"
              << "  " << graspsynth::SimulationLibraryInfo() << "\n"
              << "  " << graspsynth::SolverLibraryInfo() << "\n"
              << "  MuJoCo " << graspsynth::MujocoVersion()
              << (graspsynth::MujocoAvailable() ? "" : " (built without MuJoCo)") << "\n";
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
  if (RefuseUnknownCommand(app, argc, argv)) return 2;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return ParseErrorExit(app, e, argc, argv);
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
