# The man pages and the bash completion, made at build time from the built program's own --help
# (run as `cmake -DSURROGATE=EXE -DVERSION=X.Y.Z -DOUT=DIR -DGZIP=gzip -P man_page.cmake` by
# packaging/help/CMakeLists.txt). Writes, under OUT:
#   roff/surrogate.1, roff/surrogate-COMMAND.1   the pages as roff, to read or check;
#   man1/*.1.gz                                   the same, gzip -9n (Debian policy), installed;
#   completions/surrogate                         the bash completion, installed.
# The pages' date is SOURCE_DATE_EPOCH's when it is set, else -DRELEASE_DATE (the version's date,
# packaging/CMakeLists.txt), else none: never the day of the build, so that two builds of the same
# source make the same files.

cmake_minimum_required(VERSION 3.20)  # list() keeps the blank lines that separate the help's parts
foreach(v SURROGATE VERSION OUT GZIP)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "man_page.cmake needs -D${v}=...")
  endif()
endforeach()
include("${CMAKE_CURRENT_LIST_DIR}/help_text.cmake")
include("${CMAKE_CURRENT_LIST_DIR}/command_page.cmake")

set(date "${RELEASE_DATE}")
if(DEFINED ENV{SOURCE_DATE_EPOCH} AND NOT "$ENV{SOURCE_DATE_EPOCH}" STREQUAL "")
  string(TIMESTAMP date "%Y-%m-%d" UTC)  # CMake takes SOURCE_DATE_EPOCH as "now"
endif()
set(th "\"${date}\" \"Surrogate ${VERSION}\" \"Surrogate manual\"")

# surrogate.1: what the program is, its commands and exit codes from `surrogate --help`, and
# where it finds its data files.
function(write_main_page dir commands described text)
  help_lines(lines "${text}")
  list(GET lines 0 first)
  string(REGEX REPLACE "^surrogate [^:]*: " "" tagline "${first}")
  roff_escape(tagline "${tagline}")
  set(exits "")
  set(options "")
  set(section "")
  foreach(line IN LISTS lines)
    if(line MATCHES "^exit codes: (.*)$")
      set(exits "${CMAKE_MATCH_1}")
      set(section exit)
    elseif(line MATCHES "^[^ ].*:")
      set(section "${line}")
    elseif(section STREQUAL "exit" AND line MATCHES "^ +(.*)$")
      string(APPEND exits " ${CMAKE_MATCH_1}")
    elseif(NOT section STREQUAL "commands:" AND line MATCHES "^  (-[-A-Za-z0-9]*)( ([^ ]+))?  +(.*)$")
      roff_option_tag(tag "${CMAKE_MATCH_1}" "${CMAKE_MATCH_3}")
      roff_escape(l "${CMAKE_MATCH_4}")
      string(APPEND options ".TP\n${tag}\n${l}\n")
    endif()
  endforeach()
  if(exits STREQUAL "")
    message(FATAL_ERROR "`surrogate --help` has no \"exit codes:\" line")
  endif()

  set(roff ".\\\" Generated at build time from `surrogate --help` (packaging/help): do not edit.\n")
  string(APPEND roff ".TH SURROGATE 1 ${th}\n.nh\n.ad l\n.SH NAME\nsurrogate \\- ${tagline}\n"
    ".SH SYNOPSIS\n.B surrogate\n.I COMMAND\n[options]\n.br\n"
    ".B surrogate help\n.I COMMAND\n.br\n.B surrogate \\-\\-version\n"
    ".SH DESCRIPTION\n.B surrogate\nmakes ${tagline}. "
    "Each command has its own options, listed by\n.B surrogate help\n.I COMMAND\n"
    "(or\n.B surrogate\n.I COMMAND\n.BR \\-\\-help )\nand on its page,\n"
    ".BR surrogate\\-run (1)\nand the others named under SEE ALSO.\n")
  if(NOT options STREQUAL "")
    string(APPEND roff ".SH OPTIONS\n${options}")
  endif()
  string(APPEND roff ".SH COMMANDS\n")
  foreach(entry IN LISTS described)
    string(REGEX MATCH "^[^=]*" name "${entry}")
    string(REGEX REPLACE "^[^=]*=" "" what "${entry}")
    roff_escape(what "${what}")
    string(APPEND roff ".TP\n.B ${name}\n${what}\n")
  endforeach()
  # "0 success, 1 bad input, 2 ...": one entry per code.
  string(APPEND roff ".SH \"EXIT STATUS\"\n")
  string(REGEX REPLACE ", ([0-9]+) " "\n\\1 " exits "${exits}")
  string(REPLACE "\n" ";" exits "${exits}")
  foreach(entry IN LISTS exits)
    if(entry MATCHES "^([0-9]+) (.*)$")
      roff_escape(l "${CMAKE_MATCH_2}")
      string(APPEND roff ".TP\n.B ${CMAKE_MATCH_1}\n${l}\n")
    endif()
  endforeach()
  string(APPEND roff
    ".SH FILES\n.TP\n.I /usr/share/surrogate/\n"
    "The schemas, stylesheets and mapping tables Surrogate reads, and bundles into every package "
    "it writes.\nThey are looked for in\n.I share/surrogate\nbeside the\n.I bin\n"
    "folder that holds the program (so that a package unpacked into any folder finds its own),\n"
    "then in the folder the program was installed to.\n"
    "A data file missing is exit 1, \\(lqreinstall Surrogate: FILE is missing\\(rq.\n"
    ".SH ENVIRONMENT\n.TP\n.B SURROGATE_RESOURCES\n"
    "A folder looked in first, file by file, for those data files\n"
    "(for instance a stylesheet being tested); a file it does not hold is taken from the data folder.\n"
    ".TP\n.B SOURCE_DATE_EPOCH\n"
    "When set (seconds since 1970), fixes every time written into a package, so that two packs of "
    "the same capture are byte-identical.\n"
    ".TP\n.B TMPDIR\nWhere temporary folders are made (for instance by\n.BR \"verify \\-\\-reexecute\" ).\n"
    ".TP\n.B SURROGATE_PROGRESS\nSet to\n.BR lines ,\n"
    "progress is printed as lines on standard error even when it is not a terminal.\n"
    ".SH \"SEE ALSO\"\n")
  set(sep "")
  foreach(name IN LISTS commands)
    string(APPEND roff "${sep}.BR surrogate\\-${name} (1)")
    set(sep ",\n")
  endforeach()
  file(WRITE "${dir}/surrogate.1" "${roff}\n")
endfunction()

# Each help text is asked for once: `surrogate --help` in `top`, each command's in help_COMMAND,
# which the pages and the completion read.
help_run(top --help)
help_commands(commands described "${top}")
foreach(name IN LISTS commands)
  help_run(help_${name} help "${name}")
endforeach()
file(REMOVE_RECURSE "${OUT}/roff" "${OUT}/man1")  # no page of a command that is gone
file(MAKE_DIRECTORY "${OUT}/roff" "${OUT}/man1" "${OUT}/completions")
write_main_page("${OUT}/roff" "${commands}" "${described}" "${top}")
foreach(entry IN LISTS described)
  string(REGEX MATCH "^[^=]*" name "${entry}")
  string(REGEX REPLACE "^[^=]*=" "" what "${entry}")
  write_command_page("${OUT}/roff" "${name}" "${what}" "${th}" "${help_${name}}")
endforeach()

# gzip -9n: the best compression, and no file name or time stored in the .gz (reproducible).
file(GLOB pages RELATIVE "${OUT}/roff" "${OUT}/roff/*.1")
foreach(page IN LISTS pages)
  execute_process(COMMAND "${GZIP}" -9n -c "${OUT}/roff/${page}"
    OUTPUT_FILE "${OUT}/man1/${page}.gz" RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "gzip -9n ${page} failed (${rc})")
  endif()
endforeach()

include("${CMAKE_CURRENT_LIST_DIR}/completion.cmake")
write_completion("${OUT}/completions/surrogate" "${commands}" "${top}")
