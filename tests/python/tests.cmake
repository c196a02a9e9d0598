# The Python package's tests (pytest), one CTest test per file, run with the package of this
# build (build/python) and the command beside it (the tests compare the two).
if(GRASPSYNTH_BUILD_PYTHON)
  foreach(part package api kinematics demos synthesis study threads examples)
    add_test(NAME python.${part}
             COMMAND ${Python_EXECUTABLE} -m pytest -q -p no:cacheprovider
                     ${CMAKE_CURRENT_LIST_DIR}/test_${part}.py)
    set_tests_properties(python.${part} PROPERTIES
      ENVIRONMENT "PYTHONPATH=${CMAKE_BINARY_DIR}/python;GRASPSYNTH_BINARY=$<TARGET_FILE:graspsynth>;GRASPSYNTH_BUILD_DIR=${CMAKE_BINARY_DIR}"
      LABELS python TIMEOUT 600)
  endforeach()
endif()
