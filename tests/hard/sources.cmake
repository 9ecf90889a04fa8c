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

# ball_grep(FILES PATTERN HOME CONTROL BAD_VAR SEEN_VAR): reads the C and
# C++ files among FILES (the build files are the caller's) for lines that
# match PATTERN. Those of files outside HOME/ go to BAD_VAR as "file:
# line"; SEEN_VAR counts the files inside HOME/ with a line that matches
# CONTROL, the proof that PATTERN finds what it looks for.
function(ball_grep files pattern home control bad_var seen_var)
  set(_ball_bad "")
  set(_ball_seen 0)
  foreach(f ${files})
    if(f MATCHES "CMakeLists.txt$|\\.cmake$")
      continue()
    endif()
    file(STRINGS ${SOURCE_DIR}/${f} lines REGEX "${pattern}")
    if(f MATCHES "^${home}/")
      if(lines MATCHES "${control}")
        math(EXPR _ball_seen "${_ball_seen} + 1")
      endif()
      continue()
    endif()
    foreach(line ${lines})
      list(APPEND _ball_bad "${f}: ${line}")
    endforeach()
  endforeach()
  set(${bad_var} ${${bad_var}} ${_ball_bad} PARENT_SCOPE)
  set(${seen_var} ${_ball_seen} PARENT_SCOPE)
endfunction()

# ball_verdict(WHAT BAD_VAR SEEN NONE OK): fails when SEEN is 0 (with NONE:
# the check would prove nothing) or when BAD_VAR lists lines (under WHAT);
# else says OK.
function(ball_verdict what bad_var seen none ok)
  if(seen EQUAL 0)
    message(FATAL_ERROR "${none}: the check would prove nothing")
  endif()
  if(${bad_var})
    list(JOIN ${bad_var} "\n  " text)
    message(FATAL_ERROR "${what}:\n  ${text}")
  endif()
  message(STATUS "${ok}")
endfunction()

# ball_link_calls(FILE VAR): the target_link_libraries(...) calls of the
# build file FILE into VAR, white space folded to one blank each.
function(ball_link_calls f var)
  file(READ ${SOURCE_DIR}/${f} text)
  string(REGEX MATCHALL "target_link_libraries\\([^)]*\\)" calls "${text}")
  set(folded "")
  foreach(call ${calls})
    string(REGEX REPLACE "[ \t\n]+" " " call "${call}")
    list(APPEND folded "${call}")
  endforeach()
  set(${var} ${folded} PARENT_SCOPE)
endfunction()
