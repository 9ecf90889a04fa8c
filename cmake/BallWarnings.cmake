# The compiler warnings of every target the project builds, stated once:
# BALL_C_WARNINGS for C (libball, its tools, the C tests, the kit),
# BALL_CXX_WARNINGS for C++ (the server, validation, the C++ tests).
# Used as target_compile_options(<target> PRIVATE ${BALL_C_WARNINGS}).
# BALL_WERROR (on in every preset of CMakePresets.json) makes them errors.
# Generated code (fastddsgen's) is compiled with -w instead: not ours to fix.
# The outside programs of tests/consumer get BALL_C_WARNINGS too.
include_guard(GLOBAL)
set(BALL_C_WARNINGS -pedantic -Wall -Wextra -Wshadow -Wstrict-prototypes)
set(BALL_CXX_WARNINGS -Wall -Wextra -Wshadow)
if(BALL_WERROR)
  list(APPEND BALL_C_WARNINGS -Werror)
  list(APPEND BALL_CXX_WARNINGS -Werror)
endif()
