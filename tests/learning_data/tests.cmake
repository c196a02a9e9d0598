# Tests of learning_data/ (included by tests/CMakeLists.txt).
graspsynth_test(learning_data/demo_log_test.cpp LIBS graspsynth::learning_data)
graspsynth_test(learning_data/demo_directory_test.cpp LIBS graspsynth::learning_data)
graspsynth_test(learning_data/segmentation_test.cpp LIBS graspsynth::learning_data)
