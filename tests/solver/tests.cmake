# Tests of the demonstration analysis in solver/ and of `graspsynth analyze` (included by
# tests/CMakeLists.txt).
graspsynth_test(solver/table_analysis_test.cpp LIBS graspsynth::solver)
graspsynth_test(solver/wrist_line_test.cpp LIBS graspsynth::solver)
graspsynth_test(solver/analysis_report_test.cpp LIBS graspsynth::solver
                nlohmann_json::nlohmann_json)
graspsynth_test(apps/analyze_command_test.cpp LIBS graspsynth::solver
                nlohmann_json::nlohmann_json)
add_dependencies(apps_analyze_command_test graspsynth)
