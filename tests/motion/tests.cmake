graspsynth_test(motion/resample_test.cpp LIBS graspsynth::motion)
graspsynth_test(motion/interpolation_test.cpp LIBS graspsynth::motion)
graspsynth_test(motion/reach_test.cpp LIBS graspsynth::motion)
graspsynth_test(motion/joint_space_test.cpp LIBS graspsynth::motion)
