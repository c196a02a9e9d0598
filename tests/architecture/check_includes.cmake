# cmake -DBUILD_DIR=<build> -DCASES=<verdict:target:header;...> -P check_includes.cmake
# Builds each case's target (tests/architecture/tests.cmake) and checks that an allowed include
# compiles and a forbidden one fails because its header is not found. Prints every case and
# fails with the list of the cases that did not behave.
set(wrong)
foreach(case ${CASES})
  string(REPLACE ":" ";" fields "${case}")
  list(GET fields 0 verdict)
  list(GET fields 1 target)
  list(GET fields 2 header)
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${BUILD_DIR} --target ${target}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  # gcc: "fatal error: studies/study.hpp: No such file or directory";
  # clang: "fatal error: 'studies/study.hpp' file not found".
  string(REGEX MATCH "${header}'?:? (No such file or directory|file not found)" not_found "${out}")
  if(verdict STREQUAL "allowed" AND rc EQUAL 0)
    message(STATUS "ok: ${target} compiles (${header} may be included)")
  elseif(verdict STREQUAL "forbidden" AND NOT rc EQUAL 0 AND not_found)
    message(STATUS "ok: ${target} does not compile: ${header} is not on its include path")
  else()
    message(STATUS "WRONG: ${target} (${verdict}), build exit ${rc}:\n${out}")
    list(APPEND wrong ${target})
  endif()
endforeach()
if(wrong)
  message(FATAL_ERROR "include direction not enforced for: ${wrong}")
endif()
