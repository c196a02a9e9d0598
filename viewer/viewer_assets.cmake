# The browser viewer's files, copied on every build into <build>/viewer_assets, where the viewer
# server (viewer/viewer_server.cpp) reads them: the page (viewer/index.html, viewer/viewer.js) and
# three.js, vendored from viewer/node_modules (`npm ci --prefix viewer`, run by scripts/setup.sh;
# the version is pinned in viewer/package.json and viewer/package-lock.json). The copy runs on
# every build, so an `npm ci` after the configure step is picked up by the next build.
#
# Sets GRASPSYNTH_VIEWER_DIR and the target graspsynth_viewer_assets.
set(GRASPSYNTH_VIEWER_DIR ${CMAKE_BINARY_DIR}/viewer_assets)
add_custom_target(graspsynth_viewer_assets ALL
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR}/viewer
          -DDEST_DIR=${GRASPSYNTH_VIEWER_DIR} -P ${PROJECT_SOURCE_DIR}/viewer/copy_assets.cmake
  VERBATIM)
