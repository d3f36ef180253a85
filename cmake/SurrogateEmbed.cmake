# surrogate_embed(<target> HEADER <folder/name.h> NAMESPACE <ns> FILES <kName>=<file> ...)
#
# Web pages are written as web code (src/*/web/*.html, .js, .css: an editor, ESLint and Node's
# tests read them as what they are) and embedded in the program at build time, so that the
# program stays one file with no page to find at run time. Each <file> (relative to the calling
# folder) becomes `extern const char* const kName;` in namespace <ns>: its bytes as they are,
# NUL-terminated, declared in the generated header <folder/name.h> (include it as
# "folder/name.h": the generated folder is on <target>'s include path) and defined in a
# generated source added to <target>. Rebuilt when a file changes.
function(surrogate_embed target)
  cmake_parse_arguments(E "" "HEADER;NAMESPACE" "FILES" ${ARGN})
  if(NOT E_HEADER OR NOT E_NAMESPACE OR NOT E_FILES)
    message(FATAL_ERROR "surrogate_embed(${target}): HEADER, NAMESPACE and FILES are needed")
  endif()
  set(generated "${CMAKE_BINARY_DIR}/generated")
  get_filename_component(stem "${E_HEADER}" NAME_WE)
  get_filename_component(folder "${E_HEADER}" DIRECTORY)
  set(header "${generated}/${E_HEADER}")
  set(source "${generated}/${folder}/${stem}.cpp")
  set(inputs "")
  set(pairs "")
  foreach(pair ${E_FILES})
    string(REPLACE "=" ";" parts "${pair}")
    list(GET parts 0 name)
    list(GET parts 1 file)
    get_filename_component(file "${file}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
    list(APPEND inputs "${file}")
    list(APPEND pairs "${name}=${file}")
  endforeach()
  string(REPLACE ";" "|" pairs_arg "${pairs}")
  add_custom_command(
    OUTPUT "${header}" "${source}"
    COMMAND "${CMAKE_COMMAND}" "-DHEADER=${header}" "-DSOURCE=${source}" "-DINCLUDE=${E_HEADER}"
            "-DNAMESPACE=${E_NAMESPACE}" "-DPAIRS=${pairs_arg}"
            -P "${CMAKE_SOURCE_DIR}/cmake/embed_files.cmake"
    DEPENDS ${inputs} "${CMAKE_SOURCE_DIR}/cmake/embed_files.cmake"
    COMMENT "Embedding ${E_HEADER}"
    VERBATIM)
  target_sources(${target} PRIVATE "${source}" "${header}")
  target_include_directories(${target} PUBLIC "${generated}")
endfunction()
