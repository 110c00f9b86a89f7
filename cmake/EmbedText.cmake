# cmake -DINPUT=file -DOUTPUT=header -DSYMBOL=name -P EmbedText.cmake: writes a header holding
# the file's text as `inline constexpr std::string_view SYMBOL` (a raw string literal).
file(READ "${INPUT}" text)
string(FIND "${text}" ")pf_embed\"" clash)
if(NOT clash EQUAL -1)
    message(FATAL_ERROR "${INPUT} contains the raw string's delimiter")
endif()
file(WRITE "${OUTPUT}.tmp"
    "// Generated from ${INPUT} by cmake/EmbedText.cmake; do not edit.\n#pragma once\n#include <string_view>\n"
    "namespace pf {\ninline constexpr std::string_view ${SYMBOL} = R\"pf_embed(${text})pf_embed\";\n}  // namespace pf\n")
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")
