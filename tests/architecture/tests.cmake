# The direction of the modules (docs/architecture.md): a module's sources see the headers of
# the modules it links and of no other (cmake/GraspsynthOptions.cmake, graspsynth_module). Each
# case below is a source of module FROM that includes a header of module TO. The forbidden ones,
# a module including one that comes after it, must fail to compile because the header is not
# found; the allowed ones must compile, so that a tool chain broken for another reason does not
# pass the test. The cases are built, outside the default build, by one test
# (check_includes.cmake) that runs them one after the other.
set(graspsynth_include_cases
  "forbidden kinematics studies/study.hpp"
  "forbidden kinematics scene/scene_model.hpp"
  "forbidden scene simulation/trial.hpp"
  "forbidden simulation learning_data/demo_log.hpp"
  "forbidden learning_data analysis/wrist_line.hpp"
  "forbidden analysis solver/synthesis.hpp"
  "forbidden solver studies/study.hpp"
  "forbidden viewer teleop/protocol.hpp"
  "forbidden studies viewer/viewer_scene.hpp"
  "forbidden studies request/option.hpp"
  "forbidden simulation simulation_mujoco/mjcf_export.hpp"
  "forbidden simulation_mujoco gate/physics_gate.hpp"
  "forbidden solver gate/physics_gate.hpp"
  "forbidden solver simulation_mujoco/mujoco_sweep.hpp"
  "allowed studies kinematics/arm_model.hpp"
  "allowed solver analysis/wrist_line.hpp"
  "allowed teleop viewer/viewer_scene.hpp"
  "allowed request studies/study.hpp"
  "allowed simulation_mujoco simulation/trial_judge.hpp"
  "allowed request simulation_mujoco/mujoco_trial.hpp"
  "allowed gate simulation_mujoco/mujoco_sweep.hpp"
  "allowed gate solver/synthesis.hpp"
  "allowed studies gate/validated_synthesis.hpp")
set(case_targets)
foreach(case ${graspsynth_include_cases})
  string(REPLACE " " ";" fields "${case}")
  list(GET fields 0 verdict)
  list(GET fields 1 from)
  list(GET fields 2 header)
  string(MAKE_C_IDENTIFIER "${from}_includes_${header}" target)
  set(source ${CMAKE_CURRENT_BINARY_DIR}/architecture/${target}.cpp)
  file(CONFIGURE OUTPUT ${source} CONTENT "#include \"${header}\"\n")
  add_library(${target} OBJECT EXCLUDE_FROM_ALL ${source})
  target_link_libraries(${target} PRIVATE graspsynth::${from})
  list(APPEND case_targets "${verdict}:${target}:${header}")
endforeach()
add_test(NAME architecture.include_direction
         COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${CMAKE_BINARY_DIR} "-DCASES=${case_targets}"
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/architecture/check_includes.cmake)
set_tests_properties(architecture.include_direction PROPERTIES TIMEOUT 600 LABELS architecture)
