# The client library (ball/net.h): its C API with bad input, against a
# ball-server on loopback on the test's own DDS domain (cmake/dds_domains.cmake).
if(NOT TARGET ball_net)
  return()
endif()
include(${PROJECT_SOURCE_DIR}/cmake/dds_domains.cmake)

ball_dds_domain(test_net_api api_domain)
add_executable(test_net_api ${CMAKE_CURRENT_LIST_DIR}/test_net_api.c)
target_compile_options(test_net_api PRIVATE ${BALL_C_WARNINGS})
target_compile_definitions(test_net_api PRIVATE BALL_TEST_DOMAIN=${api_domain})
target_link_libraries(test_net_api PRIVATE ball_net cmocka m)
add_test(NAME test_net_api COMMAND test_net_api $<TARGET_FILE:ball-server>)
set_tests_properties(test_net_api PROPERTIES LABELS "net;dds" TIMEOUT 90)
