# Included by the guards of tests/hard (scripts run with -P): the
# repository's source and build files, for a guard to read.
#
# ball_sources(VAR DIR [SUBDIR...]): the C, C++ and CMake files under
# SOURCE_DIR/SUBDIR (the whole tree without SUBDIRs), relative to
# SOURCE_DIR, build trees (build*, out*) left out. Fails when there are
# none: a guard over no file proves nothing.
function(ball_sources var)
  if(NOT SOURCE_DIR OR NOT IS_DIRECTORY ${SOURCE_DIR})
    message(FATAL_ERROR "${CMAKE_SCRIPT_MODE_FILE}: -DSOURCE_DIR=<the repository> is required")
  endif()
  set(roots ${ARGN})
  if(NOT roots)
    set(roots .)
  endif()
  set(files "")
  foreach(root ${roots})
    set(d ${SOURCE_DIR}/${root})
    file(GLOB_RECURSE found RELATIVE ${SOURCE_DIR}
      ${d}/*.c ${d}/*.h ${d}/*.cpp ${d}/*.hpp ${d}/*.cxx ${d}/*.hxx ${d}/*.ipp
      ${d}/*.cmake ${d}/CMakeLists.txt)
    list(APPEND files ${found})
  endforeach()
  list(FILTER files EXCLUDE REGEX "^(\\./)?(build|out)")
  list(TRANSFORM files REPLACE "^\\./" "")
  list(REMOVE_DUPLICATES files)
  list(LENGTH files n)
  if(n EQUAL 0)
    message(FATAL_ERROR "no source file under ${SOURCE_DIR}/${roots}: the check would prove nothing")
  endif()
  set(${var} ${files} PARENT_SCOPE)
endfunction()
