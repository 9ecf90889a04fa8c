# The docs test can fail: run on tests/docs/broken/, a page with one mistake
# of each kind, it must fail and name each one.
foreach(mode pages commands)
  execute_process(COMMAND ${CHECK} ${SCRIPT} ${mode} --source ${SOURCE} --build ${BUILD}
    --pages tests/docs/broken/README.md tests/docs/broken/docs/page.md
    OUTPUT_VARIABLE out_${mode} ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 1)
    message(FATAL_ERROR "docs check ${mode} on the broken page: exit ${rc}, not 1\n${out_${mode}}${err}")
  endif()
endforeach()
set(expected
  "pages|link docs/nowhere.md: no file tests/docs/broken/docs/nowhere.md"
  "pages|link docs/page.md#no-such-heading: no heading or anchor #no-such-heading in tests/docs/broken/docs/page.md"
  "pages|docs/page.md, \"No such section\": no such section in tests/docs/broken/docs/page.md"
  "pages|path libball/scenes/no_such_scene.yaml: not in the repository"
  "pages|file no_such_file.c: no such file in the repository"
  "pages|`ballsim --no-such-option`: not in ballsim --help"
  "pages|`./run no-such-verb`: no such verb in ./run's usage"
  "pages|`ball_no_such_function`: no such name in the sources or ctest"
  "pages|`BALL_MAX_WALLS` = 17: the sources say 16"
  "commands|`echo the program says this` prints something else"
  "commands|`ctest --test-dir build -L no-such-label --show-only`: finds no tests"
  "commands|`false`: exit status 1"
  "commands|`true`: shown as an error, exits 0"
  "commands|`build/server/ball-server --help`: a DDS program in a runnable block needs --domain N"
  "commands|`build/server/ball-watch --domain 77 --help`: a DDS command runs only in a long block")
foreach(line ${expected})
  string(REPLACE "|" ";" parts "${line}")
  list(GET parts 0 mode)
  list(GET parts 1 text)
  string(FIND "${out_${mode}}" "${text}" at)
  if(at LESS 0)
    message(FATAL_ERROR "docs check ${mode} did not report: ${text}\n--- it printed\n${out_${mode}}")
  endif()
endforeach()
list(LENGTH expected n)
message(STATUS "the docs check reports all ${n} mistakes of the broken page")
