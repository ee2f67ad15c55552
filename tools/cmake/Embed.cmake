# Build-time embedding of shader and kernel sources (the Inviwo way: sources live in files, an
# include-aware step inlines their `#include "..."` lines, and the result is compiled into the binary).
#
#   fcc_embed(<target> PREFIX <name> FILES <file>... [INCLUDE_DIRS <dir>...] [DEPENDS <file>...])
#
# adds to <target> a generated source defining
#   std::string_view fcc::embedded::<name>(std::string_view relativePath)
# which returns the include-resolved text of one of FILES (path relative to the project root), or an
# empty view for an unknown name. The generated header is `embedded_<name>.h` in the binary dir.
set(FCC_EMBED_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/EmbedScript.cmake)

function(fcc_embed target)
  cmake_parse_arguments(E "" "PREFIX" "FILES;INCLUDE_DIRS;DEPENDS" ${ARGN})
  set(out_cpp ${CMAKE_CURRENT_BINARY_DIR}/embedded_${E_PREFIX}.cpp)
  set(out_h ${CMAKE_CURRENT_BINARY_DIR}/embedded_${E_PREFIX}.h)
  set(abs_files "")
  foreach(f IN LISTS E_FILES)
    list(APPEND abs_files ${PROJECT_SOURCE_DIR}/${f})
  endforeach()
  string(REPLACE ";" "|" files_arg "${E_FILES}")
  string(REPLACE ";" "|" dirs_arg "${E_INCLUDE_DIRS}")
  add_custom_command(
    OUTPUT ${out_cpp} ${out_h}
    COMMAND ${CMAKE_COMMAND} -DROOT=${PROJECT_SOURCE_DIR} -DPREFIX=${E_PREFIX} "-DFILES=${files_arg}"
            "-DINCLUDE_DIRS=${dirs_arg}" -DOUT_CPP=${out_cpp} -DOUT_H=${out_h} -P ${FCC_EMBED_SCRIPT}
    DEPENDS ${abs_files} ${E_DEPENDS} ${FCC_EMBED_SCRIPT}
    COMMENT "Embedding ${E_PREFIX} sources"
    VERBATIM)
  target_sources(${target} PRIVATE ${out_cpp})
  target_include_directories(${target} PUBLIC ${CMAKE_CURRENT_BINARY_DIR})
endfunction()
