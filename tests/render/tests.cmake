# The renderer: library tests (CMocka), ballrender from the command line
# (--compare's snapshot regression included), the golden frames, the proof
# that the comparison fails for a moved ball, and determinism across
# llvmpipe thread counts. docs/render.md.
add_executable(render_probe ${CMAKE_CURRENT_LIST_DIR}/render_probe.c)
target_compile_options(render_probe PRIVATE ${BALL_C_WARNINGS})
target_link_libraries(render_probe PRIVATE ball_rendertool m)

include(${CMAKE_CURRENT_LIST_DIR}/golden_cases.cmake)
ball_add_cmocka(test_render SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_render.c LIBS ball_render m LABELS render)
# the library tests measure against the goldens' comparison, stated once
target_compile_definitions(test_render PRIVATE BALL_GOLDEN_TOLERANCE=${BALL_GOLDEN_TOLERANCE}
  BALL_GOLDEN_MAX_PIXELS=${BALL_GOLDEN_MAX_PIXELS})
set(BALL_RENDER_LSAN "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_LIST_DIR}/lsan.supp")
set_property(TEST test_render APPEND PROPERTY ENVIRONMENT ${BALL_RENDER_LSAN})

set(BALL_RENDER_WORK ${CMAKE_CURRENT_BINARY_DIR}/render_work)

foreach(c ${BALL_GOLDEN_CASES})
  string(REPLACE " " ";" args "${c}")
  list(GET args 0 name)
  add_test(NAME render_golden_${name}
    COMMAND ${CMAKE_COMMAND} -DBALLRENDER=$<TARGET_FILE:ballrender> -DPROBE=$<TARGET_FILE:render_probe>
      -DSOURCE=${PROJECT_SOURCE_DIR} -DWORK=${BALL_RENDER_WORK}/golden -DCASE=${name}
      -P ${CMAKE_CURRENT_LIST_DIR}/goldens.cmake)
  set_tests_properties(render_golden_${name} PROPERTIES LABELS "render;golden" TIMEOUT 60
    ENVIRONMENT ${BALL_RENDER_LSAN})
endforeach()

set(BALL_RENDER_CASES
  help
  bad_scene
  bad_render_section
  bad_camera
  unwritable_folder
  bad_arguments
  every
  times_in_any_order
  ball_where_libball_puts_it
  explicit_camera
  threads_and_reruns
  golden_detects_moved_ball
  compare_update_then_same
  compare_one_pixel_over
  compare_missing_golden
  compare_other_size
)
foreach(case ${BALL_RENDER_CASES})
  add_test(NAME render_${case}
    COMMAND ${CMAKE_COMMAND} -DBALLRENDER=$<TARGET_FILE:ballrender> -DBALLSIM=$<TARGET_FILE:ballsim>
      -DPROBE=$<TARGET_FILE:render_probe> -DSOURCE=${PROJECT_SOURCE_DIR} -DHERE=${CMAKE_CURRENT_LIST_DIR}
      -DWORK=${BALL_RENDER_WORK}/${case} -DCASE=${case}
      -P ${CMAKE_CURRENT_LIST_DIR}/cases.cmake)
  set_tests_properties(render_${case} PROPERTIES LABELS "render;cli" TIMEOUT 60 ENVIRONMENT ${BALL_RENDER_LSAN})
endforeach()
