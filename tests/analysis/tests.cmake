# Tests of the analysis of demonstrations (analysis/) and of `graspsynth analyze`.
graspsynth_test(analysis/table_analysis_test.cpp LIBS graspsynth::analysis)
graspsynth_test(analysis/wrist_line_test.cpp LIBS graspsynth::analysis)
graspsynth_test(analysis/placement_line_test.cpp LIBS graspsynth::analysis)
graspsynth_test(analysis/analysis_report_test.cpp LIBS graspsynth::analysis
                nlohmann_json::nlohmann_json)
graspsynth_test(apps/analyze_command_test.cpp LIBS graspsynth::analysis
                nlohmann_json::nlohmann_json)
add_dependencies(apps_analyze_command_test graspsynth)
