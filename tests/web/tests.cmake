# The spectator page of ball-watch --http (docs/bots-and-watchers.md, "The spectator
# page") in a real browser: Debian's chromium, headless, driven over the
# DevTools protocol by Debian's python3 with python3-websocket (./run setup).
if(NOT TARGET ball-watch)
  return()
endif()
include(${PROJECT_SOURCE_DIR}/cmake/dds_domains.cmake)

add_executable(web_probe ${CMAKE_CURRENT_LIST_DIR}/web_probe.c)
target_include_directories(web_probe PRIVATE ${PROJECT_SOURCE_DIR}/tests/render)
target_link_libraries(web_probe PRIVATE ball_render ball_kit_headers)
target_compile_options(web_probe PRIVATE ${BALL_C_WARNINGS})

find_program(BALL_CHROMIUM NAMES chromium PATHS /usr/bin NO_DEFAULT_PATH REQUIRED)
find_program(BALL_WEB_PYTHON NAMES python3 PATHS /usr/bin NO_DEFAULT_PATH REQUIRED)
ball_dds_domain(web_page domain)
# (the page runs on the WebAssembly module: without it, BALL_BUILD_WASM off, there is no page to test)
if(TARGET ball_wasm)
  add_test(NAME web_page
    COMMAND ${BALL_WEB_PYTHON} ${CMAKE_CURRENT_LIST_DIR}/page_check.py --bin ${PROJECT_BINARY_DIR}/server
            --domain ${domain} --chromium ${BALL_CHROMIUM} --probe $<TARGET_FILE:web_probe>
            --work ${CMAKE_CURRENT_BINARY_DIR}/web_page)
  # (under ./run asan with Fast DDS 2.9's own new-delete-type mismatch waived, as ball_itest does)
  set_tests_properties(web_page PROPERTIES LABELS "dds;web" TIMEOUT 240
    PASS_REGULAR_EXPRESSION "page_check: passed" FAIL_REGULAR_EXPRESSION "FAIL"
    ENVIRONMENT_MODIFICATION "ASAN_OPTIONS=string_append::new_delete_type_mismatch=0")
endif()

# the page against hostile HTTP (docs/bots-and-watchers.md, "The page against
# hostile HTTP"): attacks from other loopback addresses, bounded in count and
# time, while Python's http.client loads the page (which needs the module)
ball_dds_domain(web_http_attack attack_domain)
if(TARGET ball_wasm)
  add_test(NAME web_http_attack
    COMMAND ${BALL_WEB_PYTHON} ${CMAKE_CURRENT_LIST_DIR}/http_attack.py --bin ${PROJECT_BINARY_DIR}/server
            --domain ${attack_domain} --work ${CMAKE_CURRENT_BINARY_DIR}/web_http_attack)
  set_tests_properties(web_http_attack PROPERTIES LABELS "web" TIMEOUT 120
    PASS_REGULAR_EXPRESSION "http_attack: passed" FAIL_REGULAR_EXPRESSION "FAIL")
endif()

# libball and the page's core on WebAssembly (cmake/BallWasm.cmake,
# server/web/wasm/page_core.cpp, server/web/page/ballwasm.js) in the browser:
# the glue's layout, the page's core over 2000 matches, and every double of
# 20,000 random segments (two seeds) equal to the native ball_segment_eval's,
# bit for bit
if(TARGET ball_wasm)
  add_test(NAME web_wasm
    COMMAND ${BALL_WEB_PYTHON} ${CMAKE_CURRENT_LIST_DIR}/wasm_check.py --chromium ${BALL_CHROMIUM}
            --probe $<TARGET_FILE:web_probe> --wasm $<TARGET_PROPERTY:ball_wasm,BALL_WASM_FILE>
            --glue ${PROJECT_SOURCE_DIR}/server/web/page/ballwasm.js --work ${CMAKE_CURRENT_BINARY_DIR}/web_wasm
            --count 10000 --seed 2026 --seed 7)
  set_tests_properties(web_wasm PROPERTIES LABELS "web" TIMEOUT 120
    PASS_REGULAR_EXPRESSION "wasm_check: passed" FAIL_REGULAR_EXPRESSION "FAIL")
endif()

# the page's core offline: the spectator and the racket tracks, fed from a Match
add_executable(test_spectator ${CMAKE_CURRENT_LIST_DIR}/test_spectator.cpp)
target_include_directories(test_spectator PRIVATE ${PROJECT_SOURCE_DIR}/tests/server ${PROJECT_SOURCE_DIR}/tests/support)
target_link_libraries(test_spectator PRIVATE ball_web ball_net_api ball_match)
target_compile_options(test_spectator PRIVATE ${BALL_CXX_WARNINGS})
add_test(NAME test_spectator COMMAND test_spectator)
set_tests_properties(test_spectator PROPERTIES LABELS "server;web" TIMEOUT 120)
