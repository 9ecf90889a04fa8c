# The client library (ball/net.h): its C API with bad input, against a
# ball-server on loopback on the test's own DDS domain (cmake/dds_domains.cmake).
# Then the client library as games use it: the examples of examples/ play
# against a ball-server and a ball-bot on loopback, the C game and its C++
# twin (example_check.py), and the Python binding under pytest
# (examples/python/test_point.py: the module's own checks, then a point).
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
# (under ./run asan with Fast DDS 2.9's own new-delete-type mismatch waived, as ball_itest does)
set_tests_properties(test_net_api PROPERTIES LABELS "net;dds" TIMEOUT 90
  ENVIRONMENT_MODIFICATION "ASAN_OPTIONS=string_append::new_delete_type_mismatch=0")

# on a secure domain: certificates made by the script ./run certs runs
add_test(NAME test_net_secure_certs
  COMMAND bash ${PROJECT_SOURCE_DIR}/server/security/certs.sh ${CMAKE_CURRENT_BINARY_DIR}/test_net_secure_certs 1)
set_tests_properties(test_net_secure_certs PROPERTIES FIXTURES_SETUP net_secure_certs LABELS "net;dds")
ball_dds_domain(test_net_secure secure_domain)
add_executable(test_net_secure ${CMAKE_CURRENT_LIST_DIR}/test_net_secure.c)
target_compile_options(test_net_secure PRIVATE ${BALL_C_WARNINGS})
target_compile_definitions(test_net_secure PRIVATE BALL_TEST_DOMAIN=${secure_domain})
target_link_libraries(test_net_secure PRIVATE ball_net cmocka)
add_test(NAME test_net_secure
  COMMAND test_net_secure $<TARGET_FILE:ball-server> ${CMAKE_CURRENT_BINARY_DIR}/test_net_secure_certs)
# (under ./run asan with Fast DDS 2.9's own new-delete-type mismatch waived, as ball_itest does)
set_tests_properties(test_net_secure PROPERTIES FIXTURES_REQUIRED net_secure_certs LABELS "net;dds" TIMEOUT 90
  ENVIRONMENT_MODIFICATION "ASAN_OPTIONS=string_append::new_delete_type_mismatch=0")

# ---- the games of examples/ and the Python binding ----------------------------
if(NOT TARGET rally_c OR NOT TARGET rally_cpp)
  return()
endif()
find_program(BALL_NET_PYTHON NAMES python3 PATHS /usr/bin NO_DEFAULT_PATH REQUIRED)

# Under ./run asan: Fast DDS 2.9's own new-delete-type mismatch waived, as
# for ball_itest and web_page.
set(ball_net_asan "ASAN_OPTIONS=string_append::new_delete_type_mismatch=0")

foreach(lang c cpp)
  ball_dds_domain(net_example_${lang} domain)
  add_test(NAME net_example_${lang}
    COMMAND ${BALL_NET_PYTHON} ${CMAKE_CURRENT_LIST_DIR}/example_check.py --bin ${PROJECT_BINARY_DIR}/server
            --example $<TARGET_FILE:rally_${lang}> --domain ${domain}
            --work ${CMAKE_CURRENT_BINARY_DIR}/net_example_${lang})
  set_tests_properties(net_example_${lang} PROPERTIES LABELS "net;dds" TIMEOUT 90
    PASS_REGULAR_EXPRESSION "example_check: passed" FAIL_REGULAR_EXPRESSION "FAIL"
    ENVIRONMENT_MODIFICATION "${ball_net_asan}")
endforeach()

# pytest is Debian's python3-pytest (./run setup); no bytecode or cache is
# written into examples/python. A skip fails the test: ctest gives the
# networked case what it needs.
ball_dds_domain(net_python domain)
set(ball_net_python_env
  "BALL_NET_LIBRARY=set:$<TARGET_FILE:ball_net>"
  "BALL_BIN=set:${PROJECT_BINARY_DIR}/server"
  "BALL_TEST_DOMAIN=set:${domain}"
  "PYTHONDONTWRITEBYTECODE=set:1")
# Python itself is no ASan program: the sanitizer's runtime is preloaded
# into it so that the ASan-built libball-net.so can load, and leaks are not
# looked for (the interpreter keeps its objects at exit by design; the C and
# C++ examples check the library's).
if(CMAKE_C_FLAGS MATCHES "sanitize=address")
  execute_process(COMMAND ${CMAKE_C_COMPILER} -print-file-name=libasan.so OUTPUT_VARIABLE ball_libasan
    OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT EXISTS "${ball_libasan}")
    message(FATAL_ERROR
      "net_python under ASan: ${CMAKE_C_COMPILER} -print-file-name=libasan.so gave \"${ball_libasan}\"")
  endif()
  list(APPEND ball_net_python_env "LD_PRELOAD=set:${ball_libasan}"
    "ASAN_OPTIONS=string_append::new_delete_type_mismatch=0:detect_leaks=0")
endif()
add_test(NAME net_python
  COMMAND ${BALL_NET_PYTHON} -m pytest -p no:cacheprovider -rs -v -s
          ${PROJECT_SOURCE_DIR}/examples/python/test_point.py --basetemp=${CMAKE_CURRENT_BINARY_DIR}/net_python)
set_tests_properties(net_python PROPERTIES LABELS "net;dds" TIMEOUT 90
  FAIL_REGULAR_EXPRESSION "[0-9]+ (skipped|failed|error)"
  ENVIRONMENT_MODIFICATION "${ball_net_python_env}")
