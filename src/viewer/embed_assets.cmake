# Writes viewer_assets.cc: the page template and the bundled script as C++ raw string literals,
# so `prs` serves and writes the viewer with no files beside it and nothing fetched.
# Usage: cmake -DPAGE=index.html -DSCRIPT=viewer.js -DOUTPUT=viewer_assets.cc -P embed_assets.cmake
set(delimiter "prs_asset")

function(append_literal var name file)
  file(READ "${file}" text)
  string(FIND "${text}" ")${delimiter}\"" clash)
  if(NOT clash EQUAL -1)
    message(FATAL_ERROR "${file} contains )${delimiter}\" and cannot be embedded as a raw string")
  endif()
  set(${var} "${${var}}const char ${name}[] = R\"${delimiter}(${text})${delimiter}\";\n" PARENT_SCOPE)
endfunction()

set(code "// Generated from src/viewer/web by src/viewer/embed_assets.cmake at build time; do not edit.\n")
string(APPEND code "#include \"viewer/assets.h\"\n\nnamespace prs::viewer {\nnamespace {\n\n")
append_literal(code kPage "${PAGE}")
append_literal(code kScript "${SCRIPT}")
string(APPEND code "\n}  // namespace\n\n")
string(APPEND code "std::string_view PageTemplate() { return {kPage, sizeof(kPage) - 1}; }\n")
string(APPEND code "std::string_view ViewerScript() { return {kScript, sizeof(kScript) - 1}; }\n")
string(APPEND code "\n}  // namespace prs::viewer\n")
file(WRITE "${OUTPUT}.tmp" "${code}")
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")
