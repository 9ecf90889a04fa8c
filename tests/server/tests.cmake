# The ball server's tests: the match, the bots and the config offline (label
# server), then the networked apps on loopback (label dds), each with a DDS
# domain id of its own so that parallel runs never meet.
if(NOT TARGET ball_match)
  return()
endif()

foreach(name test_match test_bot)
  add_executable(${name} ${CMAKE_CURRENT_LIST_DIR}/${name}.cpp)
  target_include_directories(${name} PRIVATE ${CMAKE_CURRENT_LIST_DIR})
  target_link_libraries(${name} PRIVATE ball_match)
  target_compile_options(${name} PRIVATE ${BALL_CXX_WARNINGS})
  add_test(NAME ${name} COMMAND ${name})
  set_tests_properties(${name} PROPERTIES LABELS server TIMEOUT 120)
endforeach()
