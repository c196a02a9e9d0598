graspsynth_test(teleop/protocol_test.cpp LIBS graspsynth::teleop)
graspsynth_test(teleop/packet_key_test.cpp LIBS graspsynth::teleop)
graspsynth_test(teleop/glove_map_test.cpp LIBS graspsynth::teleop)
graspsynth_test(teleop/viewer_scene_test.cpp LIBS graspsynth::teleop nlohmann_json::nlohmann_json)
graspsynth_test(teleop/viewer_server_test.cpp LIBS graspsynth::teleop)
graspsynth_test(teleop/viewer_replay_test.cpp LIBS graspsynth::teleop)
graspsynth_test(teleop/calibration_test.cpp LIBS graspsynth::teleop)
graspsynth_test(teleop/teleop_session_test.cpp LIBS graspsynth::teleop nlohmann_json::nlohmann_json)
graspsynth_test(teleop/udp_link_test.cpp LIBS graspsynth::teleop)
graspsynth_test(teleop/teleop_soak_test.cpp LIBS graspsynth::teleop)
graspsynth_test(apps/teleop_command_test.cpp LIBS graspsynth::teleop nlohmann_json::nlohmann_json)
add_dependencies(apps_teleop_command_test graspsynth)
graspsynth_test(apps/view_command_test.cpp LIBS graspsynth::learning_data)
add_dependencies(apps_view_command_test graspsynth)

# The viewer in a real headless browser: `graspsynth view` serves a small trajectory, Debian's
# chromium takes a screenshot, the test decodes the PNG and looks for the robot and the pan
# where the camera should see them. Skipped (exit 77) only when chromium is not installed.
find_package(Python3 COMPONENTS Interpreter QUIET)
if(Python3_Interpreter_FOUND)
  add_test(NAME teleop.viewer_screenshot
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/teleop/viewer_screenshot_test.py
                   --graspsynth $<TARGET_FILE:graspsynth>
                   --output ${CMAKE_CURRENT_BINARY_DIR}/viewer_screenshot.png)
  set_tests_properties(teleop.viewer_screenshot PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 120)
else()
  message(WARNING "python3 was not found: the test teleop.viewer_screenshot is not registered "
                  "(scripts/setup.sh installs python3)")
endif()
