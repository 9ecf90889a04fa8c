# The docs test (label docs): README.md and docs/*.md hold true for a newcomer
# who follows them literally. tests/docs/check_docs.py says what each part
# checks and how a code block is marked runnable (README.md points here).
# Debian's python3 is the one with python3-markdown-it (./run setup installs it).
find_program(BALL_DOCS_PYTHON NAMES python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(NOT BALL_DOCS_PYTHON)
  find_program(BALL_DOCS_PYTHON NAMES python3 REQUIRED)
endif()
set(ball_docs_check ${BALL_DOCS_PYTHON} ${CMAKE_CURRENT_LIST_DIR}/check_docs.py)
set(ball_docs_dirs --source ${PROJECT_SOURCE_DIR} --build ${PROJECT_BINARY_DIR})

# links, anchors, paths, names, every listed option in its program's --help
add_test(NAME docs_pages COMMAND ${ball_docs_check} pages ${ball_docs_dirs})
# the runnable code blocks, their outputs and example errors
add_test(NAME docs_commands COMMAND ${ball_docs_check} commands ${ball_docs_dirs})
# (under ./run asan the runnable blocks' ballrender needs the render tests'
# LeakSanitizer suppression of libOSMesa's one leak)
set(ball_docs_env "LSAN_OPTIONS=suppressions=${PROJECT_SOURCE_DIR}/tests/render/lsan.supp:print_suppressions=0")
set_tests_properties(docs_pages docs_commands PROPERTIES LABELS docs TIMEOUT 600
  ENVIRONMENT "${ball_docs_env}")
# the long runnable blocks (the demo, the benchmarks, the README's test
# command) run behind their own verb, ./run docs-long, not in this suite
# the check can fail: a page with one mistake of each kind (tests/docs/broken/)
add_test(NAME docs_check_catches COMMAND ${CMAKE_COMMAND} -DCHECK=${BALL_DOCS_PYTHON}
  "-DSCRIPT=${CMAKE_CURRENT_LIST_DIR}/check_docs.py" -DSOURCE=${PROJECT_SOURCE_DIR}
  -DBUILD=${PROJECT_BINARY_DIR} -P ${CMAKE_CURRENT_LIST_DIR}/catches.cmake)
set_tests_properties(docs_check_catches PROPERTIES LABELS docs TIMEOUT 120
  ENVIRONMENT "${ball_docs_env}")
