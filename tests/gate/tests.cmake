# Tests of the physics gate (gate/) and of `graspsynth synthesize`.
graspsynth_test(gate/grasp_quality_test.cpp LIBS graspsynth::gate)
graspsynth_test(gate/hold_margin_test.cpp LIBS graspsynth::gate)
graspsynth_test(gate/physics_gate_test.cpp LIBS graspsynth::gate)
graspsynth_test(gate/validated_synthesis_test.cpp LIBS graspsynth::gate)
graspsynth_test(gate/grasp_file_test.cpp LIBS graspsynth::gate nlohmann_json::nlohmann_json)
graspsynth_test(apps/synthesize_command_test.cpp LIBS graspsynth::gate
                nlohmann_json::nlohmann_json)
add_dependencies(apps_synthesize_command_test graspsynth)
