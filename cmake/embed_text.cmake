# Writes OUT, a C++ file defining `const char *const NAME` as the text of
# IN (a raw string literal): a file built into a library, so that it needs
# no file at run time (the client library's QoS profiles). Run at build time:
#   cmake -DIN=file -DOUT=file.cpp -DNAME=ns::name -DHEADER=decl.h -P embed_text.cmake
file(READ ${IN} text)
string(FIND "${text}" ")embedded\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${IN} holds the raw string's end mark")
endif()
file(WRITE ${OUT} "// generated from ${IN} by cmake/embed_text.cmake: do not edit\n#include \"${HEADER}\"\n\nconst char *const ${NAME} = R\"embedded(${text})embedded\";\n")
