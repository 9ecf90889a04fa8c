# The tools' cores, driven with memory streams: ballsim's arguments, output
# lines and run (libball/tools/ballsim_core.h).
ball_add_cmocka(test_ballsim_core SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_ballsim_core.c LIBS ball_simtool
  LABELS unit)
# ballrender's snapshot comparison (libball/tools/snapshot.h), the core of
# --compare and of the golden tests' render_probe
ball_add_cmocka(test_snapshot SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_snapshot.c LIBS ball_rendertool
  LABELS "unit;render")
