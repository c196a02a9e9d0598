# Tests of the requests (request/): the one description of each option, its checks, the config
# file, and the mapping onto the library's options.
graspsynth_test(request/option_test.cpp LIBS graspsynth::request)
graspsynth_test(request/requests_test.cpp LIBS graspsynth::request)
graspsynth_test(request/simulate_request_test.cpp LIBS graspsynth::request)
graspsynth_test(request/analyze_request_test.cpp LIBS graspsynth::request)
graspsynth_test(request/demos_request_test.cpp LIBS graspsynth::request)
graspsynth_test(request/view_request_test.cpp LIBS graspsynth::request)
graspsynth_test(request/kinematics_request_test.cpp LIBS graspsynth::request)
graspsynth_test(request/teleop_request_test.cpp LIBS graspsynth::request graspsynth::teleop)
