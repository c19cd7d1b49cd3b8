# Writes the man page of a tool from its own --help (the tool's and each
# subcommand's), so the page says what --help says, word for word.
#   cmake -DTOOL=path/to/topdump -DOUT=docs/man/topdump.1 -P man_page.cmake
# With -DCHECK=docs/man/topdump.1 (and OUT a scratch file) it fails when the
# committed page differs from the generated one (ctest docs.man_*).
cmake_minimum_required(VERSION 3.22)
get_filename_component(name "${TOOL}" NAME)
string(TOUPPER "${name}" upper)

function(run_help out)
  execute_process(COMMAND ${TOOL} ${ARGN} --help OUTPUT_VARIABLE text RESULT_VARIABLE rc)
  if(rc)
    message(FATAL_ERROR "${TOOL} ${ARGN} --help failed: ${rc}")
  endif()
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

# roff: a backslash is \e, a line starting with . or ' is escaped with \&,
# a hyphen in an option name is \-.
function(roff out text)
  string(REPLACE "\\" "\\e" text "${text}")
  string(REPLACE "-" "\\-" text "${text}")
  string(REGEX REPLACE "\n([.'])" "\n\\\\&\\1" text "\n${text}")
  string(SUBSTRING "${text}" 1 -1 text)
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

execute_process(COMMAND ${TOOL} --version OUTPUT_VARIABLE version OUTPUT_STRIP_TRAILING_WHITESPACE)
run_help(main)
# The first line is the description: "topdump: decode ...".
string(REGEX MATCH "^[^\n]*" first "${main}")
string(REGEX REPLACE "^[^:]*: *" "" summary "${first}")
roff(summary "${summary}")
roff(body "${main}")
set(page ".TH ${upper} 1 \"\" \"${version}\" \"TOPKit\"\n")
string(APPEND page ".SH NAME\n${name} \\- ${summary}\n")
string(APPEND page ".SH DESCRIPTION\nThe text of \\fB${name} \\-\\-help\\fR")
# Subcommands: the names listed under "Subcommands:" in --help.
set(subs "")
string(FIND "${main}" "Subcommands:" at)
if(at GREATER -1)
  string(SUBSTRING "${main}" ${at} -1 tail)
  string(REGEX MATCHALL "\n  [a-z][a-z0-9_-]*" lines "${tail}")
  foreach(l IN LISTS lines)
    string(STRIP "${l}" s)
    list(APPEND subs "${s}")
  endforeach()
  string(APPEND page " and of each subcommand's \\fB\\-\\-help\\fR")
endif()
string(APPEND page ".\n.PP\n.nf\n${body}.fi\n")
foreach(s IN LISTS subs)
  run_help(text ${s})
  roff(text "${text}")
  string(APPEND page ".SH \"${upper} ${s}\"\n.nf\n${text}.fi\n")
endforeach()
string(APPEND page ".SH SEE ALSO\n")
set(others topdump topsim topconf)
list(REMOVE_ITEM others ${name})
foreach(o IN LISTS others)
  string(APPEND page ".BR ${o} (1),\n")
endforeach()
string(APPEND page "the TOPKit README and docs/.\n")

file(WRITE "${OUT}" "${page}")
if(CHECK)
  file(READ "${CHECK}" committed)
  if(NOT page STREQUAL committed)
    message(FATAL_ERROR "${CHECK} is out of date; regenerate it with: "
                        "docs/man/regenerate.sh BUILD_DIR")
  endif()
endif()
