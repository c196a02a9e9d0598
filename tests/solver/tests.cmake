# Tests of grasp synthesis (solver/).
graspsynth_test(solver/bracket_test.cpp LIBS graspsynth::solver)
graspsynth_test(solver/line_principle_test.cpp LIBS graspsynth::solver)
graspsynth_test(solver/placement_cell_test.cpp LIBS graspsynth::solver)
graspsynth_test(solver/placement_motion_test.cpp LIBS graspsynth::solver)
graspsynth_test(solver/refinement_test.cpp LIBS graspsynth::solver)
graspsynth_test(solver/synthesis_test.cpp LIBS graspsynth::solver)
graspsynth_test(solver/synthesis_stages_test.cpp LIBS graspsynth::solver)
graspsynth_test(solver/shipped_demos_test.cpp LIBS graspsynth::solver)
