# The bash completion script, made from the help text (man_page.cmake includes this after
# help_text.cmake): the commands `surrogate --help` lists, and for each command the options its
# --help lists, which of them take a value, and the choices of those whose value is written as
# a|b|c. The script itself is surrogate.bash.in with those lists put in.

# `file`: the completion for `commands`, `top` being `surrogate --help`'s text and help_COMMAND
# (set by man_page.cmake) each command's.
function(write_completion file commands top)
  list(JOIN commands " " COMMANDS)
  # The general options: --help and --version always (src/cli/main.cpp), and any --help lists.
  help_options(top_opts top_valued top_choices "${top}")
  set(top_opts --help --version ${top_opts})
  list(REMOVE_DUPLICATES top_opts)
  list(JOIN top_opts " " TOP_OPTIONS)
  set(OPTION_CASES "")
  set(CHOICE_CASES "")
  foreach(name IN LISTS commands)
    help_options(opts valued choices "${help_${name}}")  # man_page.cmake asked for it once
    if(NOT opts)
      message(FATAL_ERROR "`surrogate help ${name}` lists no option")
    endif()
    list(JOIN opts " " opts)
    list(JOIN valued " " valued)
    string(APPEND OPTION_CASES
      "    ${name})\n      _surrogate_opts='${opts}'\n      _surrogate_valued='${valued}' ;;\n")
    foreach(entry IN LISTS choices)
      string(REGEX MATCH "^[^=]*" option "${entry}")
      string(REGEX REPLACE "^[^=]*=" "" words "${entry}")
      string(APPEND CHOICE_CASES "    '${name} ${option}') _surrogate_choices='${words}' ;;\n")
    endforeach()
  endforeach()
  string(REGEX REPLACE "\n$" "" OPTION_CASES "${OPTION_CASES}")
  string(REGEX REPLACE "\n$" "" CHOICE_CASES "${CHOICE_CASES}")
  if(CHOICE_CASES STREQUAL "")
    set(CHOICE_CASES "    *) ;;")
  endif()
  configure_file("${CMAKE_CURRENT_LIST_DIR}/surrogate.bash.in" "${file}" @ONLY)
endfunction()
