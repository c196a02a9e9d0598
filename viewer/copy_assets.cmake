# cmake -DSOURCE_DIR=<repo>/viewer -DDEST_DIR=<build>/viewer_assets -P copy_assets.cmake
# Copies the viewer's page and the vendored three.js into DEST_DIR (only files that changed).
# A missing three.js is not an error of the build: the server answers its paths with how to get
# it, and `graspsynth view` says so when it starts.
file(MAKE_DIRECTORY ${DEST_DIR})
file(COPY_FILE ${SOURCE_DIR}/index.html ${DEST_DIR}/index.html ONLY_IF_DIFFERENT)
file(COPY_FILE ${SOURCE_DIR}/viewer.js ${DEST_DIR}/viewer.js ONLY_IF_DIFFERENT)

set(three ${SOURCE_DIR}/node_modules/three)
set(vendored build/three.module.js build/three.core.js examples/jsm/controls/OrbitControls.js
             LICENSE)
set(missing)
foreach(file ${vendored})
  if(NOT EXISTS ${three}/${file})
    list(APPEND missing ${three}/${file})
  endif()
endforeach()
if(missing)
  list(GET missing 0 first)
  message(STATUS "graspsynth viewer: three.js is not vendored (${first} is missing): run "
                 "scripts/setup.sh (it runs 'npm ci --prefix viewer') and build again.")
  return()
endif()
foreach(file ${vendored})
  get_filename_component(name ${file} NAME)
  if(name STREQUAL "LICENSE")
    set(name three.LICENSE)
  endif()
  file(COPY_FILE ${three}/${file} ${DEST_DIR}/${name} ONLY_IF_DIFFERENT)
endforeach()
