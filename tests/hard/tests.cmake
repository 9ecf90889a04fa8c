# Hard cases that are not CMocka programs (docs/hard-cases.md).
# "Memory constant": the core library makes no allocation call at all, so a
# step cannot allocate. nm lists the archive's undefined symbols; none may be
# an allocator.
add_test(NAME hard_core_never_allocates
  COMMAND ${CMAKE_COMMAND} -DNM=${CMAKE_NM} -DLIB=$<TARGET_FILE:ball_static>
    -P ${CMAKE_CURRENT_LIST_DIR}/no_alloc.cmake)
set_tests_properties(hard_core_never_allocates PROPERTIES LABELS unit)

# "Public API only": nothing outside libball/src includes libball/src/internal.h.
# (These guards read the repository; each fails on an empty file list.)
add_test(NAME hard_public_api_only
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -P ${CMAKE_CURRENT_LIST_DIR}/public_api_only.cmake)
set_tests_properties(hard_public_api_only PROPERTIES LABELS unit)

# "Only server/dds knows DDS": no other file includes Fast DDS or the
# code fastddsgen generates from idl/, and only ball_dds links them.
add_test(NAME hard_dds_only_in_server_dds
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -P ${CMAKE_CURRENT_LIST_DIR}/dds_only_in_server_dds.cmake)
set_tests_properties(hard_dds_only_in_server_dds PROPERTIES LABELS unit)

# "Validation outside the tests": validation/ includes and links nothing of
# tests/, so it builds with BALL_BUILD_TESTS=OFF.
add_test(NAME hard_validation_outside_tests
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -P ${CMAKE_CURRENT_LIST_DIR}/validation_outside_tests.cmake)
set_tests_properties(hard_validation_outside_tests PROPERTIES LABELS unit)
