# Included by run_fuzz.cmake and fuzz_coverage.cmake (scripts run with -P).

# Stops unless every variable named is given (-D...); GENERATOR defaults to
# Ninja; corpus_scene and corpus_sim are the seed corpora (the scene harness
# also starts from the example scenes).
macro(ball_fuzz_require)
  foreach(var ${ARGN})
    if(NOT DEFINED ${var})
      message(FATAL_ERROR "${CMAKE_SCRIPT_MODE_FILE}: -D${var}=... is required")
    endif()
  endforeach()
  if(NOT GENERATOR)
    set(GENERATOR Ninja)
  endif()
  set(corpus_scene ${SOURCE_DIR}/tests/fuzz/corpus/scene ${SOURCE_DIR}/libball/scenes)
  set(corpus_sim ${SOURCE_DIR}/tests/fuzz/corpus/sim)
endmacro()

# Configures a clang build of the two harnesses (BALL_FUZZ=ON) in dir, with
# the extra cache options given after it, and builds them; sets CLANG.
function(ball_fuzz_build dir)
  find_program(CLANG NAMES clang clang-14)
  if(NOT CLANG)
    message(FATAL_ERROR "clang not found: install clang and libclang-rt-14-dev (./run setup does)")
  endif()
  set(CLANG ${CLANG} PARENT_SCOPE)
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${dir} -G ${GENERATOR}
      -DCMAKE_C_COMPILER=${CLANG} -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBALL_FUZZ=ON
      -DBALL_BUILD_VALIDATION=OFF ${ARGN}
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
