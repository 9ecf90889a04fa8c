# Builds the libFuzzer harnesses with clang in WORK_DIR/build and runs each
# for SECONDS from the seed corpus (docs/hard-cases.md):
#   cmake -DSOURCE_DIR=<repo> -DWORK_DIR=<dir> -DSECONDS=10
#         [-DJOBS=1] -P run_fuzz.cmake
# or, deterministically (fixed seed, a fixed number of inputs: what ctest's
# fuzz_smoke does, so that CI gives the same verdict every time):
#   ... -DRUNS_SCENE=20000 -DRUNS_SIM=2000 -P run_fuzz.cmake
# New inputs the fuzzer finds go to WORK_DIR/found/<harness>, never into the
# repository; a crash leaves its input in WORK_DIR (crash-*, leak-*, ...).
if(NOT DEFINED SECONDS AND DEFINED RUNS_SCENE)
  set(SECONDS 0)
endif()
include(${CMAKE_CURRENT_LIST_DIR}/fuzz_build.cmake)
ball_fuzz_require(SOURCE_DIR WORK_DIR SECONDS)
if(NOT JOBS)
  set(JOBS 1)
endif()
set(build ${WORK_DIR}/build)
ball_fuzz_build(${build})

set(parallel "")
if(JOBS GREATER 1)
  set(parallel -jobs=${JOBS} -workers=${JOBS})
endif()
foreach(harness scene sim)
  set(found ${WORK_DIR}/found/${harness})
  file(MAKE_DIRECTORY ${found})
  string(TOUPPER ${harness} H)
  if(DEFINED RUNS_${H})
    # the same inputs every run: the reload is timed, and the operands of
    # the comparisons the fuzzer traces (-use_cmp) include pointers, which
    # address randomisation changes run to run; as dictionary words they
    # sent two runs of one seed down different inputs after 162
    set(budget -runs=${RUNS_${H}} -seed=1 -reload=0 -use_cmp=0)
    message(STATUS "fuzz_${harness}: ${RUNS_${H}} inputs, seed 1, from ${corpus_${harness}}")
  else()
    set(budget -max_total_time=${SECONDS})
    message(STATUS "fuzz_${harness}: ${SECONDS} s from ${corpus_${harness}}")
  endif()
  execute_process(COMMAND ${build}/tests/fuzz_${harness}
      ${budget} -timeout=10 -rss_limit_mb=2048 -print_final_stats=1
      ${parallel} -artifact_prefix=${WORK_DIR}/ ${found} ${corpus_${harness}}
    WORKING_DIRECTORY ${WORK_DIR}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  string(REGEX MATCHALL "stat::number_of_executed_units: [0-9]+" runs "${out}")
  message(STATUS "fuzz_${harness}: ${runs}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "fuzz_${harness} failed (${rc}); the input is in ${WORK_DIR}:\n${out}")
  endif()
  # a harness that ran no input (an empty corpus and no budget) passed nothing
  if(NOT runs MATCHES "units: [1-9]")
    message(FATAL_ERROR "fuzz_${harness} ran no input:\n${out}")
  endif()
endforeach()
