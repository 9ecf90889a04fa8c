# Script mode: see tests.cmake.
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed: ${ARGN}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

# 1. CMake package, shared and static.
foreach(kind libball static)
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/app -B ${WORK_DIR}/app-${kind} -G ${GENERATOR}
      -DCMAKE_PREFIX_PATH=${prefix} -DBALL_TARGET=libball::${kind})
  run(${CMAKE_COMMAND} --build ${WORK_DIR}/app-${kind})
  run(${WORK_DIR}/app-${kind}/consumer)
  if(NOT last_output MATCHES "bounce at t=0.451524")
    message(FATAL_ERROR "consumer (${kind}) printed: ${last_output}")
  endif()
endforeach()

# 2. pkg-config.
find_program(PKG_CONFIG pkg-config REQUIRED)
find_program(CC NAMES cc gcc REQUIRED)
set(ENV{PKG_CONFIG_PATH} ${prefix}/lib/pkgconfig:${prefix}/lib/x86_64-linux-gnu/pkgconfig)
run(${PKG_CONFIG} --cflags --libs libball)
string(STRIP "${last_output}" flags)
separate_arguments(flags UNIX_COMMAND "${flags}")
run(${CC} -std=c99 -pedantic -Wall -Werror ${SOURCE_DIR}/app/consumer.c ${flags} -lm
    -Wl,-rpath,${prefix}/lib -Wl,-rpath,${prefix}/lib/x86_64-linux-gnu -o ${WORK_DIR}/consumer-pc)
run(${WORK_DIR}/consumer-pc)
if(NOT last_output MATCHES "bounce at t=0.451524")
  message(FATAL_ERROR "consumer (pkg-config) printed: ${last_output}")
endif()
