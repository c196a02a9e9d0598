# Tests of the demonstration analysis in solver/ and of `graspsynth analyze` (included by
# tests/CMakeLists.txt).
graspsynth_test(solver/table_analysis_test.cpp LIBS graspsynth::solver)
graspsynth_test(solver/wrist_line_test.cpp LIBS graspsynth::solver)
graspsynth_test(solver/placement_line_test.cpp LIBS graspsynth::solver)
graspsynth_test(solver/analysis_report_test.cpp LIBS graspsynth::solver
                nlohmann_json::nlohmann_json)
graspsynth_test(apps/analyze_command_test.cpp LIBS graspsynth::solver
                nlohmann_json::nlohmann_json)
add_dependencies(apps_analyze_command_test graspsynth)
# Tests of the synthesis half of solver/ and of `graspsynth synthesize`.
graspsynth_test(solver/bracket_test.cpp LIBS graspsynth::solver)
graspsynth_test(solver/line_principle_test.cpp LIBS graspsynth::solver)
graspsynth_test(solver/placement_cell_test.cpp LIBS graspsynth::solver)
graspsynth_test(solver/placement_motion_test.cpp LIBS graspsynth::solver)
graspsynth_test(solver/refinement_test.cpp LIBS graspsynth::solver)
graspsynth_test(solver/physics_gate_test.cpp LIBS graspsynth::solver)
graspsynth_test(solver/synthesis_test.cpp LIBS graspsynth::solver)
graspsynth_test(solver/synthesis_stages_test.cpp LIBS graspsynth::solver)
graspsynth_test(solver/validated_synthesis_test.cpp LIBS graspsynth::solver)
graspsynth_test(solver/grasp_file_test.cpp LIBS graspsynth::solver nlohmann_json::nlohmann_json)
graspsynth_test(apps/synthesize_command_test.cpp LIBS graspsynth::solver
                nlohmann_json::nlohmann_json)
add_dependencies(apps_synthesize_command_test graspsynth)
graspsynth_test(solver/shipped_demos_test.cpp LIBS graspsynth::solver)
# Tests of the end-to-end study (solver/study.hpp) and of `graspsynth run`.
graspsynth_test(solver/study_test.cpp LIBS graspsynth::solver nlohmann_json::nlohmann_json)
graspsynth_test(solver/study_codec_test.cpp LIBS graspsynth::solver)
graspsynth_test(apps/generalize_command_test.cpp)
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
