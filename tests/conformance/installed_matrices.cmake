# ctest driver: `cmake --install` of the build tree puts the default
# matrices under PREFIX/share/topkit/matrices, and the installed topconf,
# run from another directory with no TOPCONF_MATRIX_DIR, finds them there
# (relative to its own binary, not at a source path baked in).
include(GNUInstallDirs)
set(prefix "${BINARY_DIR}/install-matrices/prefix")
set(elsewhere "${BINARY_DIR}/install-matrices/cwd")
file(REMOVE_RECURSE "${prefix}" "${elsewhere}")
file(MAKE_DIRECTORY "${elsewhere}")
execute_process(COMMAND ${CMAKE_COMMAND} --install "${BINARY_DIR}" --prefix "${prefix}"
                --component tools OUTPUT_QUIET COMMAND_ERROR_IS_FATAL ANY)
set(dir "${prefix}/${CMAKE_INSTALL_DATADIR}/topkit/matrices")
set(topconf "${prefix}/${CMAKE_INSTALL_BINDIR}/topconf")
file(GLOB installed "${dir}/*.json")
list(LENGTH installed n)
if(n LESS 6)
  message(FATAL_ERROR "${dir}: ${n} matrices installed, expected one per model")
endif()
unset(ENV{TOPCONF_MATRIX_DIR})
execute_process(COMMAND "${topconf}" models --paths WORKING_DIRECTORY "${elsewhere}"
                OUTPUT_VARIABLE paths RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "topconf models --paths: ${rc}")
endif()
file(REAL_PATH "${dir}" real_dir)
execute_process(COMMAND "${topconf}" run --model c12 -q --json out.json
                WORKING_DIRECTORY "${elsewhere}" RESULT_VARIABLE rc
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc OR err MATCHES "not found")
  message(FATAL_ERROR "topconf run --model c12 from ${elsewhere}: ${rc}\n${out}\n${err}")
endif()
file(READ "${elsewhere}/out.json" json)
string(JSON matrix GET "${json}" matrix)
file(REAL_PATH "${matrix}" real_matrix)
if(NOT real_matrix STREQUAL "${real_dir}/c12.json")
  message(FATAL_ERROR "topconf ran ${matrix}, not the installed ${dir}/c12.json\n${paths}")
endif()
message(STATUS "topconf found ${real_matrix}")
