# Install libball into a scratch prefix, then build outside programs against
# the installed copy: the core (shared and static), the scene and render
# components, with find_package(libball [COMPONENTS ...]) and with
# pkg-config (check.cmake). The build's C flags go along: a sanitizer
# build's library needs its runtime in the programs too.
string(REPLACE ";" " " ball_consumer_warnings "${BALL_C_WARNINGS}")
add_test(NAME consumer_install
  COMMAND ${CMAKE_COMMAND}
    -DBUILD_DIR=${PROJECT_BINARY_DIR}
    -DSOURCE_DIR=${CMAKE_CURRENT_LIST_DIR}
    -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/consumer
    -DGENERATOR=${CMAKE_GENERATOR}
    "-DC_FLAGS=${CMAKE_C_FLAGS}"
    "-DLINK_FLAGS=${CMAKE_EXE_LINKER_FLAGS}"
    "-DWARNINGS=${ball_consumer_warnings}"
    -P ${CMAKE_CURRENT_LIST_DIR}/check.cmake)
# the render program's OSMesa keeps what LeakSanitizer would report (as for
# the render tests)
set_tests_properties(consumer_install PROPERTIES LABELS consumer
  ENVIRONMENT "LSAN_OPTIONS=suppressions=${PROJECT_SOURCE_DIR}/tests/render/lsan.supp")
