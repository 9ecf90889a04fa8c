# cmake -DSOURCE_DIR=<repo> -P public_api_only.cmake
# Nothing outside libball/src (and its white-box tests in libball/src/tests)
# includes the library's internals: the tools, the scene loader, the
# renderer, the server, the validation, the kit and the tests use the public
# headers in libball/include only, like any other client. Fails on an empty
# file list, and unless libball/src itself is seen including internal.h
# (else the pattern would match nothing anywhere).
include(${CMAKE_CURRENT_LIST_DIR}/sources.cmake)
ball_sources(files)
list(REMOVE_ITEM files tests/hard/public_api_only.cmake)
set(bad "")
foreach(f ${files})
  # build files may compile the library's sources (the fuzz build) but may
  # not put libball/src on a client's include path
  if(f MATCHES "CMakeLists.txt$|\\.cmake$" AND NOT f MATCHES "^libball/src/")
    file(STRINGS ${SOURCE_DIR}/${f} lines REGEX "include_directories.*libball/src[^/]*\\)")
    foreach(line ${lines})
      if(NOT (f STREQUAL "tests/fuzz/tests.cmake" AND line MATCHES "PRIVATE"))
        list(APPEND bad "${f}: ${line}")
      endif()
    endforeach()
  endif()
endforeach()
ball_grep("${files}" "#include.*(internal\\.h|libball/src)" libball/src "#include \"internal\\.h\"" bad inside)
list(LENGTH files n)
ball_verdict("libball internals used outside libball/src" bad ${inside} "no file of libball/src includes internal.h"
  "${n} files: only libball/src uses its internals (${inside} of its files do)")
