# ball_bench: what users run, in ns (docs/benchmarks.md; `./run bench`). Not a
# timed test: ctest runs it only as a short smoke run (label bench) that
# checks the program works and asserts nothing about time. Its measuring
# pieces (bench_kit) serve the accuracy report too (validation/, docs/accuracy.md).
add_library(ball_benchkit STATIC ${CMAKE_CURRENT_LIST_DIR}/bench_kit.c)
target_compile_options(ball_benchkit PRIVATE ${BALL_C_WARNINGS})
target_include_directories(ball_benchkit PUBLIC ${CMAKE_CURRENT_LIST_DIR})
target_link_libraries(ball_benchkit PUBLIC ball_scene ball_static m)

add_executable(ball_bench ${CMAKE_CURRENT_LIST_DIR}/ball_bench.c)
target_compile_options(ball_bench PRIVATE ${BALL_C_WARNINGS})
target_link_libraries(ball_bench PRIVATE ball_benchkit)
set_target_properties(ball_bench PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/tests/bench)
add_test(NAME ball_bench_smoke COMMAND ball_bench --smoke --scenes ${PROJECT_SOURCE_DIR}/libball/scenes)
set_tests_properties(ball_bench_smoke PROPERTIES LABELS bench TIMEOUT 120)
