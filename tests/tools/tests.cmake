# The tools' cores, driven with memory streams: ballsim's arguments, output
# lines and run (libball/tools/ballsim_core.h).
ball_add_cmocka(test_ballsim_core SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_ballsim_core.c LIBS ball_simtool
  LABELS unit)
