# WebAssembly modules for the browser (server/web/page/ballwasm.js): C and
# C++17 sources compiled again, with Debian 12's clang 14 for wasm32-wasi,
# into one .wasm file in the build tree; an ordinary target of the build,
# remade when a source or a header it includes changes.
#
#   ball_wasm_module(<target> OUTPUT <file.wasm>
#                    [SOURCES_OF <library target>...]  every source of these, with their include dirs
#                    [SOURCES <file.c|file.cpp>...]
#                    [INCLUDES <dir>...]
#                    EXPORTS <C function>...)
#
# The toolchain (./run setup installs it, docs/benchmarks.md "WebAssembly
# toolchain" says why this one and not emscripten): clang-14 and wasm-ld-14
# (lld-14), wasi-libc (C library and libm, from musl), libc++ and libc++abi
# for wasm32 (libc++-14-dev-wasm32, libc++abi-14-dev-wasm32) and the
# compiler's builtins (libclang-rt-14-dev-wasm32). Debian lays them out
# multiarch (/usr/include/wasm32-wasi, /usr/lib/wasm32-wasi), where clang
# looks for --target=wasm32-wasi by itself: no --sysroot.
#
# The module is a reactor (-mexec-model=reactor): no main; its _initialize
# (C++ constructors) is called once before anything else. It exports the
# functions named, malloc and free, and its memory. The floating point is the
# native build's (IEEE double, no contraction: BALL_C_FLOAT, BallFloat.cmake),
# no -ffast-math, and wasm has no fused multiply-add; libm is wasi-libc's, not
# glibc's (the test, tests/web/wasm_check.py, says what that costs).
include_guard(GLOBAL)
include(BallFloat)

option(BALL_BUILD_WASM "Build libball for the browser (WebAssembly, clang 14 + wasi-libc)" ON)

if(BALL_BUILD_WASM)
  find_program(BALL_WASM_CC clang-14)
  find_program(BALL_WASM_CXX clang++-14)
  find_program(BALL_WASM_LD wasm-ld-14)
  set(ball_wasm_missing "")
  foreach(tool BALL_WASM_CC BALL_WASM_CXX BALL_WASM_LD)
    if(NOT ${tool})
      string(APPEND ball_wasm_missing " ${tool}")
    endif()
  endforeach()
  if(NOT ball_wasm_missing)
    # where the driver finds each part for wasm32-wasi: a bare name back means not found
    foreach(part crt1-reactor.o libc.a libm.a libc++.a libc++abi.a)
      execute_process(COMMAND ${BALL_WASM_CXX} --target=wasm32-wasi -print-file-name=${part}
                      OUTPUT_VARIABLE found OUTPUT_STRIP_TRAILING_WHITESPACE)
      if(NOT IS_ABSOLUTE "${found}" OR NOT EXISTS "${found}")
        string(APPEND ball_wasm_missing " ${part}")
      endif()
    endforeach()
    execute_process(COMMAND ${BALL_WASM_CC} --target=wasm32-wasi -print-libgcc-file-name
                    OUTPUT_VARIABLE found OUTPUT_STRIP_TRAILING_WHITESPACE)
    if(NOT EXISTS "${found}")
      string(APPEND ball_wasm_missing " libclang_rt.builtins-wasm32.a")
    endif()
  endif()
  if(ball_wasm_missing)
    message(FATAL_ERROR "WebAssembly toolchain incomplete, missing:${ball_wasm_missing}. Install "
      "clang-14 lld-14 wasi-libc libc++-14-dev-wasm32 libc++abi-14-dev-wasm32 libclang-rt-14-dev-wasm32 "
      "(./run setup), or configure with -DBALL_BUILD_WASM=OFF.")
  endif()
endif()

function(ball_wasm_module target)
  cmake_parse_arguments(PARSE_ARGV 1 W "" "OUTPUT" "SOURCES_OF;SOURCES;INCLUDES;EXPORTS")
  if(NOT BALL_BUILD_WASM)
    return()
  endif()
  if(NOT W_OUTPUT OR NOT W_EXPORTS)
    message(FATAL_ERROR "ball_wasm_module(${target}): OUTPUT and EXPORTS are needed")
  endif()
  set(common --target=wasm32-wasi -O2 -DNDEBUG ${BALL_C_FLOAT})
  set(includes "")
  foreach(dir ${W_INCLUDES})
    list(APPEND includes -I${dir})
  endforeach()
  set(sources ${W_SOURCES})
  foreach(lib ${W_SOURCES_OF})
    get_target_property(lib_sources ${lib} SOURCES)
    get_target_property(lib_dir ${lib} SOURCE_DIR)
    foreach(src ${lib_sources})
      if(NOT IS_ABSOLUTE ${src})
        set(src ${lib_dir}/${src})
      endif()
      list(APPEND sources ${src})
    endforeach()
    # the library's own include dirs (its $<BUILD_INTERFACE:...> ones)
    list(APPEND includes "-I$<JOIN:$<TARGET_PROPERTY:${lib},INCLUDE_DIRECTORIES>,$<SEMICOLON>-I>")
  endforeach()

  set(objdir ${CMAKE_CURRENT_BINARY_DIR}/${target}.dir)
  set(objects "")
  set(has_cxx OFF)
  foreach(src ${sources})
    # src/x.c -> <objdir>/<parent folder>_x.c.o: unique over libball/src and tests/web
    get_filename_component(name ${src} NAME)
    get_filename_component(parent ${src} DIRECTORY)
    get_filename_component(parent ${parent} NAME)
    set(obj ${objdir}/${parent}_${name}.o)
    if(src MATCHES "\\.c$")
      set(compile ${BALL_WASM_CC} -std=c99 ${BALL_C_WARNINGS})
    elseif(src MATCHES "\\.(cpp|cc|cxx)$")
      set(compile ${BALL_WASM_CXX} -std=c++17 -fno-exceptions ${BALL_CXX_WARNINGS})
      set(has_cxx ON)
    else()
      message(FATAL_ERROR "ball_wasm_module(${target}): neither C nor C++: ${src}")
    endif()
    add_custom_command(OUTPUT ${obj}
      COMMAND ${compile} ${common} ${includes} -MD -MF ${obj}.d -c ${src} -o ${obj}
      DEPENDS ${src}
      DEPFILE ${obj}.d
      COMMENT "wasm32 ${parent}/${name}"
      COMMAND_EXPAND_LISTS VERBATIM)
    list(APPEND objects ${obj})
  endforeach()

  set(exports "")
  foreach(fn ${W_EXPORTS} malloc free)
    list(APPEND exports -Wl,--export=${fn})
  endforeach()
  # C++ needs libc++ and libc++abi, which the C++ driver links; the memory is exported by default
  if(has_cxx)
    set(link ${BALL_WASM_CXX})
  else()
    set(link ${BALL_WASM_CC})
  endif()
  add_custom_command(OUTPUT ${W_OUTPUT}
    COMMAND ${link} --target=wasm32-wasi -O2 -mexec-model=reactor ${exports} -Wl,--strip-debug
            ${objects} -o ${W_OUTPUT}
    DEPENDS ${objects}
    COMMENT "wasm32 link ${W_OUTPUT}"
    VERBATIM)
  add_custom_target(${target} ALL DEPENDS ${W_OUTPUT})
  # where the module is, for its tests: $<TARGET_PROPERTY:<target>,BALL_WASM_FILE>
  set_target_properties(${target} PROPERTIES BALL_WASM_FILE ${W_OUTPUT})
endfunction()
