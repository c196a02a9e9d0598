# Tests of the end-to-end study (studies/study.hpp) and of `graspsynth run`.
graspsynth_test(studies/study_test.cpp LIBS graspsynth::studies nlohmann_json::nlohmann_json)
graspsynth_test(studies/study_codec_test.cpp LIBS graspsynth::studies)
graspsynth_test(studies/study_fields_test.cpp LIBS graspsynth::studies nlohmann_json::nlohmann_json)
graspsynth_test(apps/generalize_command_test.cpp LIBS nlohmann_json::nlohmann_json)
add_dependencies(apps_generalize_command_test graspsynth)
graspsynth_test(apps/run_command_test.cpp LIBS nlohmann_json::nlohmann_json)
add_dependencies(apps_run_command_test graspsynth)
# The README's headline results (tests/apps/headline_results_test.cpp): Release only, about
# 8 min on 2 cores alone (20 gate replays of 34 grasps), 14 min measured with a study running
# beside it, hence the 25 min limit; label "headline" (ctest -L headline).
if(CMAKE_BUILD_TYPE STREQUAL "Release")
  add_executable(apps_headline_results_test apps/headline_results_test.cpp)
  target_link_libraries(apps_headline_results_test PRIVATE graspsynth_test_utils)
  add_dependencies(apps_headline_results_test graspsynth)
  gtest_discover_tests(apps_headline_results_test DISCOVERY_TIMEOUT 60
                       PROPERTIES TIMEOUT 1500 LABELS headline)
endif()
# The scale-out of generalize: resume after a kill, and (with MPI, not under the sanitizers,
# where Open MPI's own allocations would be reported) mpirun -n 3 against one process.
graspsynth_test(apps/scale_out_test.cpp LIBS graspsynth::common)
add_dependencies(apps_scale_out_test graspsynth)
if(GRASPSYNTH_MPI AND NOT GRASPSYNTH_SANITIZE)
  target_compile_definitions(apps_scale_out_test PRIVATE GRASPSYNTH_MPIEXEC="${MPIEXEC_EXECUTABLE}")
endif()
