# Every third-party library graspsynth uses, all from Debian 12's archive. A missing one stops
# the configure step with the package to install (scripts/setup.sh installs them all).
function(graspsynth_require found what package)
  if(NOT ${found})
    message(FATAL_ERROR "graspsynth needs ${what}: install the Debian package '${package}' "
                        "(or run scripts/setup.sh, which installs every dependency).")
  endif()
endfunction()

find_package(Eigen3 3.4 QUIET NO_MODULE)
graspsynth_require(Eigen3_FOUND "Eigen 3.4" libeigen3-dev)
find_package(Ceres 2.1 QUIET)
graspsynth_require(Ceres_FOUND "Ceres Solver 2.1" libceres-dev)
find_package(NLopt 2.7 QUIET)
graspsynth_require(NLopt_FOUND "NLopt 2.7" libnlopt-cxx-dev)
find_package(fcl 0.7 QUIET)
graspsynth_require(fcl_FOUND "FCL 0.7" libfcl-dev)
find_package(CGAL 5.5 QUIET)
graspsynth_require(CGAL_FOUND "CGAL 5.5" libcgal-dev)
find_package(urdfdom QUIET)
graspsynth_require(urdfdom_FOUND "urdfdom" liburdfdom-dev)
find_package(CLI11 QUIET)
graspsynth_require(CLI11_FOUND "CLI11" libcli11-dev)
find_package(nlohmann_json 3 QUIET)
graspsynth_require(nlohmann_json_FOUND "nlohmann-json" nlohmann-json3-dev)
find_package(Threads REQUIRED)
# HMAC-SHA256 of the teleoperation link's authenticated packets (teleop/packet_key.hpp).
find_package(OpenSSL 3 QUIET COMPONENTS Crypto)
graspsynth_require(OpenSSL_FOUND "OpenSSL 3 (libcrypto)" libssl-dev)

# ODE ships no CMake config on Debian; pkg-config 'ode'. graspsynth needs the double-precision
# build, which is what Debian's libode-dev is (checked in simulation/ at compile time and at
# first use), of the 0.16 series: the structured step (simulation/structured_step.cpp) and the
# broad phase re-derive ODE 0.16's dWorldStep and simple space, so another series is refused
# here, by the headers (simulation/library_info.cpp) and at run time.
find_package(PkgConfig QUIET)
graspsynth_require(PkgConfig_FOUND "pkg-config" pkg-config)
pkg_check_modules(ODE QUIET IMPORTED_TARGET ode)
graspsynth_require(ODE_FOUND "ODE 0.16 (double precision)" libode-dev)
if(NOT ODE_VERSION MATCHES "^0\\.16(\\.|$)")
  message(FATAL_ERROR "ODE ${ODE_VERSION} found (pkg-config 'ode'), but graspsynth needs ODE 0.16.x: "
                      "its structured step mirrors ODE 0.16's dWorldStep "
                      "(simulation/structured_step.cpp). Install libode-dev 0.16.")
endif()
# TinyXML (urdfdom's XML parser, installed with it): the robot description's joint graph is
# checked before urdfdom reads it (kinematics/robot_description.cpp).
pkg_check_modules(TINYXML QUIET IMPORTED_TARGET tinyxml)
graspsynth_require(TINYXML_FOUND "TinyXML" libtinyxml-dev)

# MPI (Open MPI, libopenmpi-dev) is optional: without it the command runs on one machine's
# threads, as before (docs/scale-out.md).
if(GRASPSYNTH_MPI)
  # the C API from C++; the deprecated C++ bindings are not used.
  set(MPI_CXX_SKIP_MPICXX ON)
  find_package(MPI QUIET COMPONENTS CXX)
  if(NOT MPI_CXX_FOUND)
    message(STATUS "graspsynth: MPI not found (Debian package libopenmpi-dev): building without it")
    set(GRASPSYNTH_MPI OFF)
  endif()
endif()

# MuJoCo (Debian's libmujoco-dev, 2.2) is optional like MPI: without it `simulate --engine
# mujoco` says that the build has no MuJoCo, and `export-mjcf` still writes its models
# (docs/mujoco.md). scripts/setup.sh installs it.
if(GRASPSYNTH_MUJOCO)
  find_package(mujoco 2.2 QUIET)
  if(NOT mujoco_FOUND)
    message(STATUS "graspsynth: MuJoCo not found (Debian package libmujoco-dev): building without it")
    set(GRASPSYNTH_MUJOCO OFF)
  else()
    # Debian's config names a qhull include folder that its packages do not install; an imported
    # target with a missing folder stops the generation, and graspsynth needs only mujoco.h.
    get_target_property(mujoco_includes mujoco::mujoco INTERFACE_INCLUDE_DIRECTORIES)
    set(mujoco_existing)
    foreach(dir ${mujoco_includes})
      if(EXISTS ${dir})
        list(APPEND mujoco_existing ${dir})
      endif()
    endforeach()
    set_target_properties(mujoco::mujoco PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${mujoco_existing}")
  endif()
endif()

if(GRASPSYNTH_BUILD_TESTS)
  find_package(GTest QUIET)
  graspsynth_require(GTest_FOUND "GoogleTest" "libgtest-dev libgmock-dev")
endif()
if(GRASPSYNTH_BUILD_BENCHMARKS)
  find_package(benchmark QUIET)
  graspsynth_require(benchmark_FOUND "Google Benchmark" libbenchmark-dev)
  find_package(orocos_kdl QUIET)
  graspsynth_require(orocos_kdl_FOUND "orocos KDL 1.5 (benchmarks only)" liborocos-kdl-dev)
endif()

if(GRASPSYNTH_BUILD_PYTHON)
  # Debian's numpy, pytest and matplotlib belong to Debian's interpreter; a python3 found first
  # on the PATH (pyenv, a virtual environment) may lack them. -DPython_EXECUTABLE=... overrides.
  if(NOT Python_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "Python interpreter of the module")
  endif()
  find_package(Python 3.9 QUIET COMPONENTS Interpreter Development.Module)
  graspsynth_require(Python_FOUND "Python 3 with its headers" python3-dev)
  # a module the interpreter must import: numpy (the module), pytest (the tests).
  function(graspsynth_require_python_module module package)
    execute_process(COMMAND ${Python_EXECUTABLE} -c "import ${module}"
                    RESULT_VARIABLE missing OUTPUT_QUIET ERROR_QUIET)
    if(missing)
      set(module_found FALSE)
    else()
      set(module_found TRUE)
    endif()
    graspsynth_require(module_found "${module} for ${Python_EXECUTABLE}" ${package})
  endfunction()
  graspsynth_require_python_module(numpy python3-numpy)
  if(GRASPSYNTH_BUILD_TESTS)
    graspsynth_require_python_module(pytest python3-pytest)
  endif()
  set(PYBIND11_FINDPYTHON ON)
  find_package(pybind11 2.10 QUIET CONFIG)
  graspsynth_require(pybind11_FOUND "pybind11 2.10" pybind11-dev)
endif()
