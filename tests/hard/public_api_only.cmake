# Nothing outside libball/src (and its white-box tests in libball/src/tests)
# includes the library's internals: the tools, the scene loader, the
# renderer, the server, the validation and the tests use the public headers
# in libball/include only, like any other client.
file(GLOB_RECURSE files RELATIVE ${SOURCE_DIR}
  ${SOURCE_DIR}/*.c ${SOURCE_DIR}/*.h ${SOURCE_DIR}/*.cpp ${SOURCE_DIR}/*.hpp ${SOURCE_DIR}/*.cxx
  ${SOURCE_DIR}/*.cmake ${SOURCE_DIR}/CMakeLists.txt)
set(bad "")
foreach(f ${files})
  if(f MATCHES "^(build|out)" OR f MATCHES "^libball/src/" OR f STREQUAL "tests/hard/public_api_only.cmake")
    continue()
  endif()
  file(STRINGS ${SOURCE_DIR}/${f} lines REGEX "(#include.*(internal\\.h|libball/src)|libball/src[^/]*\\))")
  foreach(line ${lines})
    if(f MATCHES "CMakeLists.txt$|\\.cmake$")
      # build files may compile the library's sources (the fuzz build) but
      # may not put libball/src on a client's include path
      if(NOT line MATCHES "include_directories")
        continue()
      endif()
      if(f STREQUAL "tests/fuzz/tests.cmake" AND line MATCHES "PRIVATE")
        continue()
      endif()
    endif()
    list(APPEND bad "${f}: ${line}")
  endforeach()
endforeach()
list(LENGTH files n)
if(bad)
  list(JOIN bad "\n  " text)
  message(FATAL_ERROR "libball internals used outside libball/src:\n  ${text}")
endif()
message(STATUS "${n} files: only libball/src uses its internals")
