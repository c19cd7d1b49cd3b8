# ctest driver: `cmake --install` of the build tree puts the tools and their
# man pages (docs/man/) under the prefix, and man reads each page; the
# Wireshark dissector goes to share/topkit/wireshark/top.lua, the same bytes
# as `topdump wireshark` writes.
set(prefix "${BINARY_DIR}/install-man/prefix")
file(REMOVE_RECURSE "${prefix}")
execute_process(COMMAND ${CMAKE_COMMAND} --install "${BINARY_DIR}" --prefix "${prefix}"
                --component tools RESULT_VARIABLE rc OUTPUT_QUIET)
if(rc)
  message(FATAL_ERROR "install failed: ${rc}")
endif()
include(GNUInstallDirs)
foreach(tool topdump topsim topconf)
  set(page "${prefix}/${CMAKE_INSTALL_MANDIR}/man1/${tool}.1")
  if(NOT EXISTS "${page}" OR NOT EXISTS "${prefix}/${CMAKE_INSTALL_BINDIR}/${tool}")
    message(FATAL_ERROR "${tool} or ${page} not installed")
  endif()
  find_program(MAN man)
  if(MAN)
    execute_process(COMMAND ${MAN} -l "${page}" OUTPUT_VARIABLE text RESULT_VARIABLE rc
                    ERROR_VARIABLE err)
    if(rc OR NOT text MATCHES "--version")
      message(FATAL_ERROR "man -l ${page} failed (${rc}): ${err}")
    endif()
  endif()
endforeach()
set(plugin "${prefix}/${CMAKE_INSTALL_DATADIR}/topkit/wireshark/top.lua")
if(NOT EXISTS "${plugin}")
  message(FATAL_ERROR "${plugin} not installed")
endif()
execute_process(COMMAND "${prefix}/${CMAKE_INSTALL_BINDIR}/topdump" wireshark
                OUTPUT_VARIABLE fresh RESULT_VARIABLE rc)
file(READ "${plugin}" installed)
if(rc OR NOT fresh STREQUAL installed)
  message(FATAL_ERROR "${plugin} differs from `topdump wireshark` (${rc})")
endif()
