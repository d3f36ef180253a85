# Reading the program's own --help text at build time, for the man pages (man_page.cmake) and
# the bash completion (completion.cmake): the text is run out of the built binary, so that the
# pages and the completion say what the program says, never a copy kept by hand.
#
# The help's layout (src/cli/*.cpp): "usage: ..." first, a paragraph, then sections, each a
# heading line ending in ':' (not indented) followed by indented entries:
#   "  --opt VALUE   text"  (an option; text continued on lines indented further)
#   "  surrogate ..."       (an example; "      what it does" under it)
#   "  N  text"             (an exit code; text continued on lines indented further)

# `surrogate ARGS...`'s standard output in `out`; a failure stops the build with what it said.
function(help_run out)
  execute_process(COMMAND "${SURROGATE}" ${ARGN}
    OUTPUT_VARIABLE text ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0 OR text STREQUAL "")
    message(FATAL_ERROR "`surrogate ${ARGN}` failed (${rc}): ${err}")
  endif()
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

# The lines of `text` as a CMake list. The characters CMake lists treat specially (';', '[', ']'
# and '\') are kept as placeholders inside the list; help_decode gives them back.
function(help_lines out text)
  string(REPLACE "\\" "<~bs~>" text "${text}")
  string(REPLACE ";" "<~sc~>" text "${text}")
  string(REPLACE "[" "<~lb~>" text "${text}")
  string(REPLACE "]" "<~rb~>" text "${text}")
  string(REGEX REPLACE "\n$" "" text "${text}")
  string(REPLACE "\n" ";" text "${text}")
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

function(help_decode out text)
  string(REPLACE "<~sc~>" ";" text "${text}")
  string(REPLACE "<~lb~>" "[" text "${text}")
  string(REPLACE "<~rb~>" "]" text "${text}")
  string(REPLACE "<~bs~>" "\\" text "${text}")
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

# One line of help text as roff: '\' printed as \e, a hyphen that starts a word (an option, a
# negative number) as \- so that `man` searches and copy-and-paste find "--title", and a line
# that would begin with '.' or "'" (a roff request) guarded by \&. Leading spaces go: in a man
# page they would break the filled paragraph.
function(roff_escape out text)
  help_decode(t "${text}")
  string(REGEX REPLACE "^[ ]+" "" t "${t}")
  string(REPLACE "\\" "\\e" t "${t}")
  string(REGEX REPLACE "(^|[] (`'\"/,=|[])-" "\\1\\\\-" t "${t}")
  while(t MATCHES "\\\\--")
    string(REPLACE "\\--" "\\-\\-" t "${t}")
  endwhile()
  # and the hyphens inside an option's name: --bag-info is \-\-bag\-info.
  while(t MATCHES "\\\\-[A-Za-z0-9]+-")
    string(REGEX REPLACE "\\\\-([A-Za-z0-9]+)-" "\\\\-\\1\\\\-" t "${t}")
  endwhile()
  if(t MATCHES "^[.']")
    set(t "\\&${t}")
  endif()
  set(${out} "${t}" PARENT_SCOPE)
endfunction()

# The options a command's help lists, in order (`out`), those of them that take a value
# (`out_valued`), and for those whose value is a choice written in lower case (bag|ocfl|eark),
# entries "OPTION=choice choice ..." (`out_choices`).
function(help_options out out_valued out_choices text)
  help_lines(lines "${text}")
  set(section "")
  set(options "")
  set(valued "")
  set(choices "")
  foreach(line IN LISTS lines)
    if(line MATCHES "^[^ ].*:$")
      set(section "${line}")
    elseif(NOT section MATCHES "^(examples|exit codes):$"
           AND line MATCHES "^  (-[-A-Za-z0-9]*)( ([^ ]+))?(  |$)")
      set(name "${CMAKE_MATCH_1}")
      set(value "${CMAKE_MATCH_3}")
      if(NOT name IN_LIST options)
        list(APPEND options "${name}")
        if(NOT value STREQUAL "")
          list(APPEND valued "${name}")
          if(value MATCHES "^[a-z0-9]+(\\|[a-z0-9]+)+$")
            string(REPLACE "|" " " value "${value}")
            list(APPEND choices "${name}=${value}")
          endif()
        endif()
      endif()
    endif()
  endforeach()
  set(${out} "${options}" PARENT_SCOPE)
  set(${out_valued} "${valued}" PARENT_SCOPE)
  set(${out_choices} "${choices}" PARENT_SCOPE)
endfunction()

# The commands `surrogate --help` lists under "commands:", and their one-line descriptions
# (`out_lines`: one entry per command, "NAME=TEXT", placeholders kept).
function(help_commands out out_lines text)
  help_lines(lines "${text}")
  set(in_commands FALSE)
  set(names "")
  set(described "")
  foreach(line IN LISTS lines)
    if(line MATCHES "^[^ ].*:")
      set(in_commands FALSE)
      if(line STREQUAL "commands:")
        set(in_commands TRUE)
      endif()
    elseif(in_commands AND line MATCHES "^  ([a-z][a-z0-9-]*)  +(.*)$")
      list(APPEND names "${CMAKE_MATCH_1}")
      list(APPEND described "${CMAKE_MATCH_1}=${CMAKE_MATCH_2}")
    elseif(in_commands AND line MATCHES "^    +(.*)$" AND described)
      list(POP_BACK described last)
      list(APPEND described "${last} ${CMAKE_MATCH_1}")
    endif()
  endforeach()
  if(NOT names)
    message(FATAL_ERROR "`surrogate --help` lists no command under \"commands:\"")
  endif()
  set(${out} "${names}" PARENT_SCOPE)
  set(${out_lines} "${described}" PARENT_SCOPE)
endfunction()
