# shaderlab_embed_text(<input file> <output .cpp> <C++ symbol>): writes a source file defining
# `extern const char* const <symbol>` holding the file's text, so a program carries the file
# (e.g. docs/lab.schema.json) without depending on the source tree at run time. Re-runs when the
# input changes.
function(shaderlab_embed_text input output symbol)
  file(READ "${input}" text)
  string(FIND "${text}" ")sl_embed\"" clash)
  if(NOT clash EQUAL -1)
    message(FATAL_ERROR "${input} contains the raw-string delimiter used to embed it")
  endif()
  set(content "// Generated from ${input} by cmake/EmbedText.cmake; do not edit.\nnamespace shaderlab {\nextern const char* const ${symbol};\nconst char* const ${symbol} = R\"sl_embed(${text})sl_embed\";\n}  // namespace shaderlab\n")
  if(EXISTS "${output}")
    file(READ "${output}" old)
  endif()
  if(NOT "${old}" STREQUAL "${content}")
    file(WRITE "${output}" "${content}")
  endif()
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${input}")
endfunction()
