# cmake -DSOURCE_DIR=<repo> -P dds_only_in_server_dds.cmake
# Only server/dds/ knows DDS: no other file includes a Fast DDS header
# (fastdds/, fastrtps/, fastcdr/) or a header fastddsgen generates from
# idl/*.idl (<stem>.h, <stem>PubSubTypes.h, <stem>TypeObject.h, ...), and
# no target links the generated code (ball_idl) or Fast DDS's libraries
# but server/dds's own libraries (ball_dds, ball_dds_client, ball_dds_testing) and ball_idl
# itself, which is that generated code. Fails
# on an empty file list, and unless server/dds itself is seen including
# Fast DDS (else the patterns would match nothing anywhere).
include(${CMAKE_CURRENT_LIST_DIR}/sources.cmake)
ball_sources(files)
file(GLOB idls RELATIVE ${SOURCE_DIR}/idl ${SOURCE_DIR}/idl/*.idl)
if(NOT idls)
  message(FATAL_ERROR "no ${SOURCE_DIR}/idl/*.idl: no generated header to look for")
endif()
set(stems "")
foreach(idl ${idls})
  get_filename_component(stem ${idl} NAME_WE)
  list(APPEND stems ${stem})
endforeach()
list(JOIN stems "|" stems)
# a generated header is included by its bare name (its folder is on the
# include path), never as <ball/...>
set(generated "#[ \t]*include[ \t]*[<\"](${stems})(PubSubTypes|TypeObject|CdrAux|TypeObjectSupport)?\\.(h|hpp|ipp)[>\"]")
set(fastdds "#[ \t]*include[ \t]*[<\"](fastdds|fastrtps|fastcdr)/")
list(REMOVE_ITEM files tests/hard/dds_only_in_server_dds.cmake)
set(bad "")
foreach(f ${files})
  if(f MATCHES "CMakeLists.txt$|\\.cmake$")
    # target_link_libraries(<target> ...) calls that name the generated
    # code or Fast DDS: only ball_dds's and ball_idl's
    ball_link_calls(${f} calls)
    foreach(call ${calls})
      if(call MATCHES "^target_link_libraries\\( ?([^ )]+)" AND NOT CMAKE_MATCH_1 MATCHES "^(ball_dds|ball_dds_client|ball_dds_testing|ball_idl)$"
         AND call MATCHES " (ball_idl|fastrtps|fastcdr|fastdds[^ )]*)[ )]")
        list(APPEND bad "${f}: ${call}")
      endif()
    endforeach()
  endif()
endforeach()
ball_grep("${files}" "${fastdds}|${generated}" server/dds "${fastdds}" bad inside)
list(LENGTH files n)
ball_verdict("Fast DDS or its generated code used outside server/dds" bad ${inside}
  "no file of server/dds includes Fast DDS"
  "${n} files: only server/dds uses Fast DDS and the generated code (${inside} of its files do)")
