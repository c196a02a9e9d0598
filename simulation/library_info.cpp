#include "simulation/library_info.hpp"

#include <dlfcn.h>
#include <ode/ode.h>
#include <ode/version.h>

#include <string>
#include <string_view>

#include "common/errors.hpp"

#ifndef dDOUBLE
#error "graspsynth needs ODE built in double precision (Debian's libode-dev is)"
#endif

// the headers' version (cmake/GraspsynthDependencies.cmake checks pkg-config's at configure time).
static_assert(std::string_view(dODE_VERSION).substr(0, 5) == "0.16.",
              "graspsynth's structured step mirrors ODE 0.16.x (simulation/structured_step.cpp); "
              "these ODE headers are of another version (ode/version.h's dODE_VERSION)");

namespace graspsynth {
namespace {

// The file the ODE library was loaded from (its soname, as the dynamic linker found it), or ""
// when ODE is linked into the program itself.
std::string LoadedOdeFile() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&dWorldStep), &info) == 0 || !info.dli_fname) return "";
  const std::string file = info.dli_fname;
  const std::string base = file.substr(file.find_last_of('/') + 1);
  return base.rfind("libode.", 0) == 0 ? file : "";
}

}  // namespace

void RequireSupportedOde() {
  // the header's precision must match the library's, or every call corrupts memory.
  if (!dCheckConfiguration("ODE_double_precision")) {
    throw InputError(
        "the ODE library loaded is not the double-precision build that graspsynth was compiled "
        "for (ODE reports: " +
        std::string(dGetConfiguration()) +
        "; expected ODE_double_precision); install Debian's libode-dev and rebuild");
  }
  // ODE 0.16 reports no version at run time: its shared library's name says the series.
  const std::string file = LoadedOdeFile();
  const std::string base = file.substr(file.find_last_of('/') + 1);
  if (!file.empty() && base.rfind(kOdeLibraryName, 0) != 0) {
    throw InputError("the ODE library loaded (" + file + ") is not of the ODE " + kOdeSeries +
                     " series (" + kOdeLibraryName +
                     "), whose dWorldStep graspsynth's structured step mirrors; graspsynth was "
                     "compiled against ODE " dODE_VERSION " headers");
  }
}

std::string SimulationLibraryInfo() {
  RequireSupportedOde();
  const std::string file = LoadedOdeFile();
  return std::string("ODE " dODE_VERSION " (") + dGetConfiguration() + ")" +
         (file.empty() ? std::string(" linked in") : " from " + file);
}

}  // namespace graspsynth
