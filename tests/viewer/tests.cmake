# Tests of the browser viewer (viewer/): its scene, server and replay, and the page in Chromium.
graspsynth_test(viewer/viewer_scene_test.cpp LIBS graspsynth::viewer nlohmann_json::nlohmann_json)
graspsynth_test(viewer/viewer_server_test.cpp LIBS graspsynth::viewer)
graspsynth_test(viewer/viewer_replay_test.cpp LIBS graspsynth::viewer)
graspsynth_test(apps/view_command_test.cpp LIBS graspsynth::learning_data)
add_dependencies(apps_view_command_test graspsynth)

# The viewer in a real headless browser: `graspsynth view` serves a small trajectory (joint
# commands), a grasp that lifts the pan and the trial record of one that drops it (physics);
# Debian's chromium takes a screenshot of each, the test decodes the PNGs and looks for the robot
# and the pan where the camera should see them, the pan's height and the outcome banner. Skipped (exit 77) only when chromium is not installed.
find_package(Python3 COMPONENTS Interpreter QUIET)
if(Python3_Interpreter_FOUND)
  add_test(NAME viewer.viewer_screenshot
           COMMAND ${Python3_EXECUTABLE}
                   ${CMAKE_CURRENT_SOURCE_DIR}/viewer/viewer_screenshot_test.py
                   --graspsynth $<TARGET_FILE:graspsynth>
                   --output ${CMAKE_CURRENT_BINARY_DIR}/viewer_screenshot.png
                   --output-lift ${CMAKE_CURRENT_BINARY_DIR}/viewer_lift.png
                   --output-drop ${CMAKE_CURRENT_BINARY_DIR}/viewer_drop.png)
  set_tests_properties(viewer.viewer_screenshot PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 400)
else()
  message(WARNING "python3 was not found: the test viewer.viewer_screenshot is not registered "
                  "(scripts/setup.sh installs python3)")
endif()
