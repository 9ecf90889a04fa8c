# What the command-line cases (tests/cli, tests/render) expect of a run,
# given RC, OUT and ERR (its exit status, stdout, stderr) and CASE.
function(fail what)
  message(FATAL_ERROR "${CASE}: ${what}\n--- exit status: ${RC}\n--- stdout:\n${OUT}\n--- stderr:\n${ERR}")
endfunction()

function(expect_rc want)
  if(NOT "${RC}" STREQUAL "${want}")
    fail("expected exit status ${want}")
  endif()
endfunction()

function(expect_out regex)
  if(NOT "${OUT}" MATCHES "${regex}")
    fail("stdout does not match: ${regex}")
  endif()
endfunction()

function(expect_err regex)
  if(NOT "${ERR}" MATCHES "${regex}")
    fail("stderr does not match: ${regex}")
  endif()
endfunction()
