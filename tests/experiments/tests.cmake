# experiments/tune_operator.py through the built command: a short search on one strategy.
find_package(Python3 COMPONENTS Interpreter QUIET)
if(Python3_Interpreter_FOUND)
  add_test(NAME experiments.tune_operator
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/experiments/tune_operator_test.py
                   --graspsynth $<TARGET_FILE:graspsynth>
                   --script ${PROJECT_SOURCE_DIR}/experiments/tune_operator.py
                   --config ${PROJECT_SOURCE_DIR}/learning_data/demos/operator.json)
  set_tests_properties(experiments.tune_operator PROPERTIES TIMEOUT 300)
  # experiments/benchmark_context.py on a sample, and the committed perf_*.json hold no
  # absolute path.
  add_test(NAME experiments.benchmark_context
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/experiments/benchmark_context_test.py
                   --script ${PROJECT_SOURCE_DIR}/experiments/benchmark_context.py
                   --results ${PROJECT_SOURCE_DIR}/experiments/results)
  set_tests_properties(experiments.benchmark_context PROPERTIES TIMEOUT 60)
endif()
