// graspsynth._core: the extension module behind the Python package graspsynth
// (python/graspsynth/__init__.py adds the pure-Python layer).

#include "common/errors.hpp"
#include "python/bindings.hpp"

PYBIND11_MODULE(_core, m) {
  namespace py = pybind11;
  m.doc() = "graspsynth's C++ library: kinematics, demonstrations, physics, synthesis, studies";
  // bad input (a file, an argument) raises graspsynth.InputError, a ValueError, with the C++
  // message: the file, line, field and value at fault.
  m.attr("__version__") = GRASPSYNTH_VERSION;
  auto& input_error =
      py::register_exception<graspsynth::InputError>(m, "InputError", PyExc_ValueError);
  input_error.attr("__doc__") =
      "Bad input (a file, an argument): the message names the file, line, field and value at "
      "fault. A ValueError.";
  graspsynth::python::BindResults(m);  // the classes and enums the others return
  graspsynth::python::BindKinematics(m);
  graspsynth::python::BindDemos(m);
  graspsynth::python::BindSimulation(m);
  graspsynth::python::BindLibrary(m);
  graspsynth::python::BindStudy(m);
  graspsynth::python::BindRequests(m);
}
