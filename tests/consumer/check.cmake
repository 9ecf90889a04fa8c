# Script mode: see tests.cmake. Installs the build into WORK_DIR/prefix and
# builds outside programs against the installed copy. C_FLAGS and
# LINK_FLAGS are the build's own (the programs of a sanitizer build need its
# runtime too), WARNINGS its C warnings (cmake/BallWarnings.cmake).
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed: ${ARGN}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

# Runs a program built against the installed copy; its output must match.
function(expect what regex)
  run(${ARGN})
  if(NOT last_output MATCHES "${regex}")
    message(FATAL_ERROR "${what} printed: ${last_output}")
  endif()
  message(STATUS "${what}: ${last_output}")
endfunction()

run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
set(scene ${prefix}/share/libball/scenes/dropped_ball.yaml)
# what each program prints (its comment derives the numbers)
set(core_says "bounce at t=0.451524")
set(scene_says "dropped_ball: bounce at t=0.619098 y=0.120000")
set(render_says "frame 64x48 at t=0.500: ball at y=0.773750, png read back the same")
set(net_says "net: a value is outside its allowed range: domain 300 is not in \\[0, 232\\]; not yet: the server has not said enough; racket")
separate_arguments(c_flags UNIX_COMMAND "${C_FLAGS}")
separate_arguments(link_flags UNIX_COMMAND "${LINK_FLAGS}")
separate_arguments(warnings UNIX_COMMAND "${WARNINGS}")

# 1. The CMake package: the core, shared and static; the scene and render
# components; a component it does not have fails the configure.
foreach(kind libball static)
  set(app ${WORK_DIR}/app-${kind})
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/app -B ${app} -G ${GENERATOR}
      -DCMAKE_PREFIX_PATH=${prefix} -DBALL_TARGET=libball::${kind}
      "-DCMAKE_C_FLAGS=${C_FLAGS} ${WARNINGS}" "-DCMAKE_EXE_LINKER_FLAGS=${LINK_FLAGS}")
  run(${CMAKE_COMMAND} --build ${app})
  expect("consumer (${kind})" "${core_says}" ${app}/consumer)
endforeach()
expect("consumer_scene (libball::scene)" "${scene_says}" ${WORK_DIR}/app-libball/consumer_scene ${scene})
expect("consumer_render (libball::render)" "${render_says}" ${WORK_DIR}/app-libball/consumer_render ${scene}
  ${WORK_DIR}/frame.png)
expect("consumer_net (libball::net)" "${net_says}" ${WORK_DIR}/app-libball/consumer_net)
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/nosuch -B ${WORK_DIR}/nosuch -G ${GENERATOR}
    -DCMAKE_PREFIX_PATH=${prefix}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT "${out}${err}" MATCHES "nosuch")
  message(FATAL_ERROR "find_package(libball COMPONENTS scene nosuch) did not fail:\n${out}\n${err}")
endif()

# 2. pkg-config: libball, libball-scene, libball-render, libball-net; each
# .pc file says all its library needs (no -lm added here).
find_program(PKG_CONFIG pkg-config REQUIRED)
find_program(CC NAMES cc gcc REQUIRED)
set(ENV{PKG_CONFIG_PATH} ${prefix}/lib/pkgconfig:${prefix}/lib/x86_64-linux-gnu/pkgconfig)
foreach(pc libball libball-scene libball-render libball-net)
  if(pc STREQUAL libball)
    set(src consumer)
    set(args "")
    set(says "${core_says}")
  elseif(pc STREQUAL libball-scene)
    set(src consumer_scene)
    set(args ${scene})
    set(says "${scene_says}")
  elseif(pc STREQUAL libball-render)
    set(src consumer_render)
    set(args ${scene} ${WORK_DIR}/frame-pc.png)
    set(says "${render_says}")
  else()
    set(src consumer_net)
    set(args "")
    set(says "${net_says}")
  endif()
  run(${PKG_CONFIG} --cflags --libs ${pc})
  string(STRIP "${last_output}" flags)
  separate_arguments(flags UNIX_COMMAND "${flags}")
  run(${CC} -std=c99 ${warnings} ${c_flags} ${SOURCE_DIR}/app/${src}.c ${flags} ${link_flags}
      -Wl,-rpath,${prefix}/lib -Wl,-rpath,${prefix}/lib/x86_64-linux-gnu -o ${WORK_DIR}/${src}-pc)
  expect("${src} (pkg-config ${pc})" "${says}" ${WORK_DIR}/${src}-pc ${args})
endforeach()
