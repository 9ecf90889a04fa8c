# Included by run_fuzz.cmake and fuzz_coverage.cmake (scripts run with -P).

# Stops unless every variable named is given (-D...); corpus_scene and
# corpus_sim are the seed corpora (the scene harness also starts from the
# example scenes).
macro(ball_fuzz_require)
  foreach(var ${ARGN})
    if(NOT DEFINED ${var})
      message(FATAL_ERROR "${CMAKE_SCRIPT_MODE_FILE}: -D${var}=... is required")
    endif()
  endforeach()
  set(corpus_scene ${SOURCE_DIR}/tests/fuzz/corpus/scene ${SOURCE_DIR}/libball/scenes)
  set(corpus_sim ${SOURCE_DIR}/tests/fuzz/corpus/sim)
endmacro()

# Configures the clang build of the two harnesses in dir with the preset
# fuzz (CMakePresets.json: BALL_FUZZ=ON, its build type), clang as found
# here, and the extra cache options given after dir; builds them; sets CLANG.
function(ball_fuzz_build dir)
  find_program(CLANG NAMES clang clang-14)
  if(NOT CLANG)
    message(FATAL_ERROR "clang not found: install clang and libclang-rt-14-dev (./run setup does)")
  endif()
  set(CLANG ${CLANG} PARENT_SCOPE)
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} --preset fuzz -B ${dir}
      -DCMAKE_C_COMPILER=${CLANG} ${ARGN}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "configuring the clang fuzz build in ${dir} failed:\n${out}")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${dir} --target fuzz_scene fuzz_sim
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "building the fuzz harnesses in ${dir} failed:\n${out}")
  endif()
endfunction()
