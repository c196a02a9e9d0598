graspsynth_test(teleop/protocol_test.cpp LIBS graspsynth::teleop)
graspsynth_test(teleop/glove_map_test.cpp LIBS graspsynth::teleop)
