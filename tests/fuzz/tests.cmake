# libFuzzer harnesses (docs/hard-cases.md, "Fuzzing").
#
# libFuzzer needs clang, the main build uses gcc: the harnesses are built only
# in a separate clang build with BALL_FUZZ=ON (preset "fuzz"), which compiles
# the library sources again with the fuzzer, AddressSanitizer and
# UndefinedBehaviorSanitizer instrumentation. In any other build one ctest
# test (label "fuzz") configures and builds that clang build under the build
# tree and runs each harness briefly from the seed corpus in corpus/.
option(BALL_FUZZ "Build the libFuzzer harnesses (clang only)" OFF)
option(BALL_FUZZ_COVERAGE "With BALL_FUZZ: instrument for source-based coverage instead of the sanitizers" OFF)
set(BALL_FUZZ_RUNS_SCENE 50000 CACHE STRING "Inputs fuzz_scene runs in the fuzz_smoke test (seed 1)")
set(BALL_FUZZ_RUNS_SIM 5000 CACHE STRING "Inputs fuzz_sim runs in the fuzz_smoke test (seed 1)")

if(BALL_FUZZ)
  if(NOT CMAKE_C_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "BALL_FUZZ needs clang (configure with -DCMAKE_C_COMPILER=clang or --preset fuzz)")
  endif()
  set(BALL_FUZZ_FLAGS -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all
      -fno-omit-frame-pointer -g -O1)
  set(BALL_FUZZ_LINK -fsanitize=fuzzer,address,undefined)
  if(BALL_FUZZ_COVERAGE)
    # clang's source-based coverage (fuzz_coverage.cmake): the fuzzer still
    # drives the inputs, the harnesses' checks still abort; no sanitizers,
    # whose code is no part of the report
    set(BALL_FUZZ_FLAGS -fsanitize=fuzzer-no-link -fprofile-instr-generate -fcoverage-mapping -g -O1)
    set(BALL_FUZZ_LINK -fsanitize=fuzzer -fprofile-instr-generate)
  endif()
  # the core and the scene loader, instrumented: the same sources as ball_static and ball_scene
  set(fuzz_sources "")
  foreach(lib ball_static ball_scene)
    get_target_property(lib_sources ${lib} SOURCES)
    get_target_property(lib_dir ${lib} SOURCE_DIR)
    foreach(src ${lib_sources})
      if(IS_ABSOLUTE ${src})
        list(APPEND fuzz_sources ${src})
      else()
        list(APPEND fuzz_sources ${lib_dir}/${src})
      endif()
    endforeach()
  endforeach()
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(BALL_FUZZ_YAML REQUIRED IMPORTED_TARGET yaml-0.1)
  add_library(ball_fuzz_lib STATIC ${fuzz_sources})
  target_include_directories(ball_fuzz_lib PUBLIC ${PROJECT_SOURCE_DIR}/libball/include
    PRIVATE ${PROJECT_SOURCE_DIR}/libball/src)
  target_compile_options(ball_fuzz_lib PRIVATE ${BALL_FUZZ_FLAGS})
  target_link_libraries(ball_fuzz_lib PUBLIC PkgConfig::BALL_FUZZ_YAML m)
  foreach(harness fuzz_scene fuzz_sim)
    # both harnesses assert the same frame invariants (invariants.c)
    add_executable(${harness} ${CMAKE_CURRENT_LIST_DIR}/${harness}.c ${CMAKE_CURRENT_LIST_DIR}/invariants.c)
    target_compile_options(${harness} PRIVATE ${BALL_FUZZ_FLAGS})
    target_link_options(${harness} PRIVATE ${BALL_FUZZ_LINK})
    target_link_libraries(${harness} PRIVATE ball_fuzz_lib)
    if(BALL_FUZZ_COVERAGE)
      target_compile_definitions(${harness} PRIVATE FZ_KEEP_GOING) # invariants.h
    endif()
  endforeach()
  # in the fuzz build: replay the seed corpus once (a regression test)
  add_test(NAME fuzz_scene_corpus COMMAND fuzz_scene -runs=0 ${CMAKE_CURRENT_LIST_DIR}/corpus/scene
    ${PROJECT_SOURCE_DIR}/libball/scenes)
  add_test(NAME fuzz_sim_corpus COMMAND fuzz_sim -runs=0 ${CMAKE_CURRENT_LIST_DIR}/corpus/sim)
  # the inputs of library bugs the harnesses found and that are still open
  # (found/README.md): this test fails until they are fixed
  add_test(NAME fuzz_sim_found COMMAND fuzz_sim -runs=0 ${CMAKE_CURRENT_LIST_DIR}/found/sim)
  set_tests_properties(fuzz_scene_corpus fuzz_sim_corpus fuzz_sim_found PROPERTIES LABELS fuzz)
else()
  add_test(NAME fuzz_smoke
    COMMAND ${CMAKE_COMMAND}
      -DSOURCE_DIR=${PROJECT_SOURCE_DIR}
      -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/fuzz
      -DRUNS_SCENE=${BALL_FUZZ_RUNS_SCENE}
      -DRUNS_SIM=${BALL_FUZZ_RUNS_SIM}
      -P ${CMAKE_CURRENT_LIST_DIR}/run_fuzz.cmake)
  set_tests_properties(fuzz_smoke PROPERTIES LABELS fuzz TIMEOUT 900)
endif()
