# Compiler flags shared by every graspsynth target, applied through graspsynth_options.
add_library(graspsynth_options INTERFACE)
target_compile_options(graspsynth_options INTERFACE -Wall -Wextra -Wpedantic)
if(GRASPSYNTH_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "GRASPSYNTH_FUZZ needs clang (libFuzzer): configure with "
                        "-DCMAKE_CXX_COMPILER=clang++ (scripts/fuzz.sh does)")
  endif()
  # libFuzzer's coverage in every library; the fuzz targets link its driver (fuzz/).
  target_compile_options(graspsynth_options INTERFACE -fsanitize=fuzzer-no-link)
  set(GRASPSYNTH_SANITIZE ON)
endif()
if(GRASPSYNTH_SANITIZE)
  target_compile_options(graspsynth_options INTERFACE
    -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  target_link_options(graspsynth_options INTERFACE -fsanitize=address,undefined)
  # lets heavy tests (long simulations, large random sweeps) run fewer cases when sanitized.
  target_compile_definitions(graspsynth_options INTERFACE GRASPSYNTH_SANITIZED=1)
endif()

# graspsynth_module(NAME SOURCES ... DEPS ...): one library target per module, with the
# graspsynth:: alias. Headers are included as "module/file.hpp" from the repository root.
function(graspsynth_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(graspsynth_${name} ${ARG_SOURCES})
  add_library(graspsynth::${name} ALIAS graspsynth_${name})
  target_include_directories(graspsynth_${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(graspsynth_${name} PUBLIC graspsynth_options ${ARG_PUBLIC_DEPS}
                                           PRIVATE ${ARG_PRIVATE_DEPS})
  if(GRASPSYNTH_BUILD_PYTHON)
    # linked into the Python extension, a shared object. Only the libraries: the executables'
    # objects stay as they were (and in ccache).
    set_target_properties(graspsynth_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
    # -fPIC alone lets the compiler assume any global function may be replaced at load time,
    # so it stops inlining them into each other within a file. Nothing here is replaced
    # (benchmarks/README.md, "Python").
    target_compile_options(graspsynth_${name} PRIVATE -fno-semantic-interposition)
  endif()
endfunction()
