# Hard cases that are not CMocka programs (docs/hard-cases.md).
# "Memory constant": the core library makes no allocation call at all, so a
# step cannot allocate. nm lists the archive's undefined symbols; none may be
# an allocator.
add_test(NAME hard_core_never_allocates
  COMMAND ${CMAKE_COMMAND} -DNM=${CMAKE_NM} -DLIB=$<TARGET_FILE:ball_static>
    -P ${CMAKE_CURRENT_LIST_DIR}/no_alloc.cmake)
set_tests_properties(hard_core_never_allocates PROPERTIES LABELS unit)

# "Public API only": nothing outside libball/src includes libball/src/internal.h.
add_test(NAME hard_public_api_only
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -P ${CMAKE_CURRENT_LIST_DIR}/public_api_only.cmake)
set_tests_properties(hard_public_api_only PROPERTIES LABELS unit)
