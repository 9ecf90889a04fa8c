# ball_bench: what users run, in ns (docs/benchmarks.md; `./run bench`). Not a
# timed test: ctest runs it only as a short smoke run (label bench) that
# checks the program works and asserts nothing about time. Its measuring
# pieces are kit/bench_kit.h, shared with the accuracy report (validation/,
# docs/accuracy.md).
add_executable(ball_bench ${CMAKE_CURRENT_LIST_DIR}/ball_bench.c)
target_compile_options(ball_bench PRIVATE ${BALL_C_WARNINGS})
target_link_libraries(ball_bench PRIVATE ball_kit)
set_target_properties(ball_bench PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/tests/bench)
add_test(NAME ball_bench_smoke COMMAND ball_bench --smoke --scenes ${PROJECT_SOURCE_DIR}/libball/scenes)
set_tests_properties(ball_bench_smoke PROPERTIES LABELS bench TIMEOUT 120)

# ball_bench_libm: libball's own exp, expm1, log and log1p against glibc's, in
# ns per call (docs/benchmarks.md; `./run bench`). White box (it calls the
# library's internal ball__ functions, so it lives beside the white-box tests
# in libball/src/tests/ and links the static library); a smoke run in ctest.
add_executable(ball_bench_libm ${PROJECT_SOURCE_DIR}/libball/src/tests/bench_elementary.c)
target_compile_options(ball_bench_libm PRIVATE ${BALL_C_WARNINGS})
target_link_libraries(ball_bench_libm PRIVATE ball_kit ball_static m)
set_target_properties(ball_bench_libm PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/tests/bench)
add_test(NAME ball_bench_libm_smoke COMMAND ball_bench_libm --smoke)
set_tests_properties(ball_bench_libm_smoke PROPERTIES LABELS bench TIMEOUT 120)

# net_query: the client library's ball query against ball_segment_eval, in
# one run (./run bench-client, tests/bench/client_bench.py; docs/client.md)
if(TARGET ball_net)
  add_executable(net_query ${CMAKE_CURRENT_LIST_DIR}/net_query.c)
  target_compile_options(net_query PRIVATE ${BALL_C_WARNINGS})
  target_link_libraries(net_query PRIVATE ball_net)
  set_target_properties(net_query PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/tests/bench)
endif()
