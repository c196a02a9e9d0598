#pragma once

#include <string>

namespace graspsynth {

/// The ODE release series whose dWorldStep the structured step re-derives
/// (simulation/structured_step.cpp), as pkg-config and ode/version.h spell it, and the shared
/// library's file name in that series (libtool's current version 8: ODE 0.16.0 to 0.16.x).
inline constexpr const char* kOdeSeries = "0.16";
inline constexpr const char* kOdeLibraryName = "libode.so.8";

/// Throws InputError, naming what was found and what is expected, when the libode loaded is not
/// the double-precision build that the headers describe (every call would then corrupt memory)
/// or not of the ODE 0.16 series (the structured step mirrors ODE 0.16's dWorldStep, and the
/// broad phase its simple space). The simulation calls it before its first use of ODE
/// (EnsureOdeThread).
void RequireSupportedOde();

/// The ODE build the simulation module runs on, e.g. "ODE 0.16.2 (ODE ODE_EXT_trimesh ...
/// ODE_double_precision) from /usr/lib/x86_64-linux-gnu/libode.so.8". Throws what
/// RequireSupportedOde throws.
std::string SimulationLibraryInfo();

}  // namespace graspsynth
