# Install libball into a scratch prefix, then build two tiny programs against
# the installed copy: one with find_package(libball), one with pkg-config.
add_test(NAME consumer_install
  COMMAND ${CMAKE_COMMAND}
    -DBUILD_DIR=${PROJECT_BINARY_DIR}
    -DSOURCE_DIR=${CMAKE_CURRENT_LIST_DIR}
    -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/consumer
    -DGENERATOR=${CMAKE_GENERATOR}
    -P ${CMAKE_CURRENT_LIST_DIR}/check.cmake)
set_tests_properties(consumer_install PROPERTIES LABELS consumer)
