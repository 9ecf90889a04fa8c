# ballsim from the command line: --help, every example scene and the events
# it must produce, argument errors, scene errors and the trajectory files.
# Each case is a block of cases.cmake run with cmake -P, so expectations are
# plain CMake regexes and number comparisons, free of shell quoting.
set(BALL_CLI_CASES
  help
  default_is_tennis
  tennis
  football_wall
  dropped_ball
  darts
  juggling
  juggling_exact_at_any_fps
  rally_easy
  rally_mid
  rally_advanced
  serve
  smash_6hz
  drop_shot
  bad_script
  overrides
  out_csv
  out_jsonl
  format_option
  bad_numbers
  bad_options
  missing_scene
  bad_scenes
  output_injection
  big_numbers
  keys
)
foreach(case ${BALL_CLI_CASES})
  add_test(NAME cli_${case}
    COMMAND ${CMAKE_COMMAND}
      -DBALLSIM=$<TARGET_FILE:ballsim>
      -DSCENES=${PROJECT_SOURCE_DIR}/libball/scenes
      -DHERE=${CMAKE_CURRENT_LIST_DIR}
      -DWORK=${CMAKE_CURRENT_BINARY_DIR}/cli_work/${case}
      -DCASE=${case}
      -P ${CMAKE_CURRENT_LIST_DIR}/cases.cmake)
  set_tests_properties(cli_${case} PROPERTIES LABELS cli TIMEOUT 60)
endforeach()

# docs/scenes.md's key table is the field table (ballsim --keys).
add_test(NAME docs_scene_keys_current
  COMMAND ${CMAKE_COMMAND} -DBALLSIM=$<TARGET_FILE:ballsim> -DDOC=${PROJECT_SOURCE_DIR}/docs/scenes.md
    -P ${CMAKE_CURRENT_LIST_DIR}/keys_doc.cmake)
set_tests_properties(docs_scene_keys_current PROPERTIES LABELS cli)
