# experiments/tune_operator.py through the built command: a short search on one strategy.
find_package(Python3 COMPONENTS Interpreter QUIET)
if(Python3_Interpreter_FOUND)
  add_test(NAME experiments.tune_operator
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/experiments/tune_operator_test.py
                   --graspsynth $<TARGET_FILE:graspsynth>
                   --script ${PROJECT_SOURCE_DIR}/experiments/tune_operator.py
                   --config ${PROJECT_SOURCE_DIR}/learning_data/demos/operator.json)
  set_tests_properties(experiments.tune_operator PROPERTIES TIMEOUT 300)
endif()
