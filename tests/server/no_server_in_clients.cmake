# The client programs and the client library hold nothing of the server's
# match, host or loop (docs/design.md, "Who links what"): no symbol of
# ballsrv::Match, ballsrv::Host or ballsrv::ServerLoop in any of FILES, and
# some in SERVER (so that the check can fail).
#   cmake -DNM=nm -DFILES="a;b" -DSERVER=ball-server -P no_server_in_clients.cmake
set(pattern "ballsrv::(Match|Host|ServerLoop)::")
function(symbols file out)
  execute_process(COMMAND ${NM} -C ${file} OUTPUT_VARIABLE text RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${NM} -C ${file}: ${err}")
  endif()
  string(REGEX MATCHALL "[^\n]*${pattern}[^\n]*" found "${text}")
  set(${out} "${found}" PARENT_SCOPE)
endfunction()
symbols(${SERVER} in_server)
list(LENGTH in_server n)
if(n EQUAL 0)
  message(FATAL_ERROR "${SERVER} has no symbol matching ${pattern}: the check would see nothing")
endif()
foreach(file ${FILES})
  symbols(${file} found)
  list(LENGTH found n)
  if(n GREATER 0)
    list(GET found 0 first)
    message(FATAL_ERROR "${file} links the server's match, host or loop: ${n} symbols, e.g. ${first}")
  endif()
  message(STATUS "${file}: none of the server's")
endforeach()
