# One command's man page, surrogate-COMMAND.1, made from `surrogate COMMAND --help`: the usage
# line as the SYNOPSIS, the paragraph as the DESCRIPTION, each option group as a subsection of
# OPTIONS with one .TP entry per option, the examples as EXAMPLES and the exit codes as EXIT STATUS.
# Needs help_text.cmake's functions.

# The roff of a SYNOPSIS from a usage text "surrogate run CAPTURE [options]": the program and
# command in bold, the rest as written.
function(roff_synopsis out usage command)
  roff_escape(rest "${usage}")
  string(REGEX REPLACE "^surrogate ${command}( |$)" "" rest "${rest}")
  set(${out} ".B surrogate ${command}\n${rest}\n" PARENT_SCOPE)
endfunction()

# The .TP tag of an option line's first part, "--title TEXT": the option in bold, its value in
# italics.
function(roff_option_tag out name value)
  roff_escape(n "${name}")
  set(tag "\\fB${n}\\fR")
  if(NOT value STREQUAL "")
    roff_escape(v "${value}")
    set(tag "${tag} \\fI${v}\\fR")
  endif()
  set(${out} "${tag}" PARENT_SCOPE)
endfunction()

# The body of a man page (every section after SYNOPSIS) from a command's help `text`, whose first
# line is its usage; `out_usage` gets that usage without "usage: ".
function(roff_help_body out out_usage text)
  help_lines(lines "${text}")
  list(POP_FRONT lines usage)
  string(REGEX REPLACE "^usage: " "" usage "${usage}")
  set(roff ".SH DESCRIPTION\n")
  set(state description)  # description, options, examples, exit
  set(opened FALSE)       # whether .SH OPTIONS has been written
  foreach(line IN LISTS lines)
    if(line STREQUAL "")
      if(state STREQUAL "description" AND NOT roff STREQUAL ".SH DESCRIPTION\n")
        set(state between)
      endif()
      continue()
    endif()
    if(line MATCHES "^[^ ].*:$" AND NOT state STREQUAL "description")
      string(REGEX REPLACE ":$" "" heading "${line}")
      if(heading STREQUAL "examples")
        set(state examples)
        string(APPEND roff ".SH EXAMPLES\n")
      elseif(heading STREQUAL "exit codes")
        set(state exit)
        string(APPEND roff ".SH EXIT STATUS\n")
      else()
        set(state options)
        if(NOT opened)
          string(APPEND roff ".SH OPTIONS\n")
          set(opened TRUE)
        endif()
        roff_escape(h "${heading}")
        if(heading MATCHES "^the options of")
          # "the options of `surrogate run`, for when ...": a sentence between groups.
          string(APPEND roff ".PP\n${h}:\n")
        else()
          string(APPEND roff ".SS \"${h}\"\n")
        endif()
      endif()
    elseif(state MATCHES "^(description|between)$" AND line MATCHES "^[^ ]")
      # The paragraph, or one more after a blank line.
      if(state STREQUAL "between")
        string(APPEND roff ".PP\n")
        set(state description)
      endif()
      roff_escape(l "${line}")
      string(APPEND roff "${l}\n")
    elseif(state STREQUAL "options" AND line MATCHES "^  (-[-A-Za-z0-9]*)( ([^ ]+))?(  +(.*))?$")
      roff_option_tag(tag "${CMAKE_MATCH_1}" "${CMAKE_MATCH_3}")
      roff_escape(l "${CMAKE_MATCH_5}")
      string(APPEND roff ".TP\n${tag}\n")
      if(NOT l STREQUAL "")
        string(APPEND roff "${l}\n")
      endif()
    elseif(state STREQUAL "examples" AND line MATCHES "^  (surrogate .*)$")
      roff_escape(l "${CMAKE_MATCH_1}")
      string(APPEND roff ".PP\n.EX\n${l}\n.EE\n")
    elseif(state STREQUAL "exit" AND line MATCHES "^  ([0-9]+)  +(.*)$")
      roff_escape(l "${CMAKE_MATCH_2}")
      string(APPEND roff ".TP\n.B ${CMAKE_MATCH_1}\n${l}\n")
    elseif(state STREQUAL "examples" AND line MATCHES "^   +")
      # What an example does: indented under its command line.
      roff_escape(l "${line}")
      string(APPEND roff ".RS\n${l}\n.RE\n")
    elseif(line MATCHES "^   +" AND NOT state STREQUAL "between")
      # An option's or exit code's text, continued.
      roff_escape(l "${line}")
      string(APPEND roff "${l}\n")
    else()
      message(FATAL_ERROR "a line of --help that the man page cannot place: \"${line}\"\n"
                          "(packaging/help/command_page.cmake reads the layout src/cli writes)")
    endif()
  endforeach()
  set(${out} "${roff}" PARENT_SCOPE)
  set(${out_usage} "${usage}" PARENT_SCOPE)
endfunction()

# surrogate-COMMAND.1 in `dir`, its NAME line saying `summary` (the command list's line), from
# `text`, the command's --help.
function(write_command_page dir command summary th text)
  roff_help_body(body usage "${text}")
  roff_synopsis(synopsis "${usage}" "${command}")
  roff_escape(what "${summary}")
  string(TOUPPER "surrogate-${command}" title)
  roff_escape(title "${title}")
  file(WRITE "${dir}/surrogate-${command}.1"
    ".\\\" Generated at build time from `surrogate ${command} --help` (packaging/help): do not edit.\n"
    ".TH ${title} 1 ${th}\n.nh\n.ad l\n"
    ".SH NAME\nsurrogate\\-${command} \\- ${what}\n"
    ".SH SYNOPSIS\n${synopsis}"
    "${body}"
    ".SH SEE ALSO\n.BR surrogate (1)\n")
endfunction()
