# The documentation's tests (tests/docs/).
# - docs.readme_results: the README's table of headline results is the one
#   scripts/readme_results.py makes from experiments/results/.
# - docs.examples.PAGE: every example of README.md and docs/*.md runs as written
#   (tests/docs/doc_examples.py says how a page marks a reduced or skipped one). Release only:
#   the examples run the physics, which the sanitizers make ten times slower. Label "docs".
find_package(Python3 COMPONENTS Interpreter QUIET)
if(Python3_Interpreter_FOUND)
  add_test(NAME docs.readme_results
           COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/scripts/readme_results.py --check)
  set_tests_properties(docs.readme_results PROPERTIES LABELS docs)
  # - docs.reference.iiwa14_*: the second robot's checks (docs/reference/checks/, numpy): its
  #   URDF against the published joint positions, and its placement at the study's table.
  #   They run in /usr/bin/python3 (the scripts' Python, which has numpy) and are skipped
  #   (exit 77) where numpy is missing.
  find_program(graspsynth_system_python python3 PATHS /usr/bin NO_DEFAULT_PATH)
  if(graspsynth_system_python)
    foreach(check iiwa14_fk_check iiwa14_placement)
      add_test(NAME docs.reference.${check}
               COMMAND ${graspsynth_system_python}
                       ${PROJECT_SOURCE_DIR}/docs/reference/checks/${check}.py)
      set_tests_properties(docs.reference.${check} PROPERTIES TIMEOUT 300 LABELS docs
                                                              SKIP_RETURN_CODE 77)
    endforeach()
  endif()
  if(CMAKE_BUILD_TYPE STREQUAL "Release")
    file(GLOB graspsynth_doc_pages CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/docs/*.md)
    foreach(page ${PROJECT_SOURCE_DIR}/README.md ${graspsynth_doc_pages})
      get_filename_component(name ${page} NAME_WE)
      add_test(NAME docs.examples.${name}
               COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/docs/doc_examples.py
                       --source ${PROJECT_SOURCE_DIR} --build ${PROJECT_BINARY_DIR} ${page})
      set_tests_properties(docs.examples.${name} PROPERTIES TIMEOUT 1500 LABELS docs)
    endforeach()
  endif()
endif()
