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

# graspsynth_module(NAME SOURCES ... PUBLIC_DEPS ... PRIVATE_DEPS ...): one library target per
# module folder, with the graspsynth:: alias. Headers are included as "module/file.hpp".
#
# The direction of the modules is enforced by the include path: a module's target exports an
# include folder that holds its own folder only (<build>/module_include/NAME/NAME, a link to
# NAME/ in the sources), never the repository root. A source sees the headers of its own module
# and of the modules it links (PUBLIC_DEPS, PRIVATE_DEPS, and theirs), so an include in the wrong
# direction, say kinematics including "studies/study.hpp", fails to compile
# (tests/architecture/).
function(graspsynth_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(graspsynth_${name} ${ARG_SOURCES})
  add_library(graspsynth::${name} ALIAS graspsynth_${name})
  # the folder's own name: a second target of a folder (mpi, in common/) shows the same headers.
  get_filename_component(folder ${CMAKE_CURRENT_SOURCE_DIR} NAME)
  set(include_root ${CMAKE_BINARY_DIR}/module_include/${name})
  file(MAKE_DIRECTORY ${include_root})
  file(CREATE_LINK ${CMAKE_CURRENT_SOURCE_DIR} ${include_root}/${folder} SYMBOLIC)
  target_include_directories(graspsynth_${name} PUBLIC ${include_root})
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
