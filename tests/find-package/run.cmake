# ctest driver: install the build tree to a temporary prefix, then configure,
# build and run the consumer against it.
set(prefix "${BINARY_DIR}/find-package/prefix")
set(work "${BINARY_DIR}/find-package/build")
file(REMOVE_RECURSE "${prefix}" "${work}")
execute_process(COMMAND ${CMAKE_COMMAND} --install "${BINARY_DIR}" --prefix "${prefix}"
                --component Unspecified RESULT_VARIABLE rc OUTPUT_QUIET)
if(rc)
  message(FATAL_ERROR "install failed: ${rc}")
endif()
# A request for a version the package is not (major 99) must fail to
# configure: the version file is installed and read.
execute_process(COMMAND ${CMAKE_COMMAND} -S "${SOURCE_DIR}/tests/find-package" -B "${work}-99"
                -DCMAKE_PREFIX_PATH=${prefix} -DTOPKIT_WANT_VERSION=99
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
file(REMOVE_RECURSE "${work}-99")
if(rc EQUAL 0)
  message(FATAL_ERROR "find_package(topkit 99) succeeded: no version file installed?")
endif()
if(EXISTS "${prefix}/include/top/detail")
  message(FATAL_ERROR "top/detail/ is installed: it is not public")
endif()
# The installed headers are the library's contract: none names a speed
# device of the tree's own (the decode shape cache, its slots, the session's
# prefilter: protocol/internal/top/detail/, docs/perf/decisions.md) or
# includes a detail/ header.
file(GLOB_RECURSE installed_headers "${prefix}/include/*")
if(NOT installed_headers)
  message(FATAL_ERROR "no header installed under ${prefix}/include")
endif()
set(internal_names "[A-Za-z_]*Cache[A-Za-z_]*|ShapeSlot|shape_slot|may_matter_to_diagnoses")
string(APPEND internal_names "|ident_key|#[ \t]*include[ \t]*[<\"]top/detail/")
foreach(header IN LISTS installed_headers)
  file(READ "${header}" text)
  string(REGEX MATCH "${internal_names}" hit "${text}")
  if(hit)
    message(FATAL_ERROR "${header} names `${hit}`: an installed header holds the API only; "
                        "move it behind protocol/internal/top/detail/")
  endif()
endforeach()
execute_process(COMMAND ${CMAKE_COMMAND} -S "${SOURCE_DIR}/tests/find-package" -B "${work}"
                -DCMAKE_PREFIX_PATH=${prefix} -DTOPKIT_WANT_VERSION=0.1
                -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_CXX_STANDARD=20
                "-DCMAKE_CXX_FLAGS=${FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${LDFLAGS}"
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(rc)
  message(FATAL_ERROR "configure failed: ${rc}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build "${work}" RESULT_VARIABLE rc OUTPUT_QUIET)
if(rc)
  message(FATAL_ERROR "build failed: ${rc}")
endif()
execute_process(COMMAND "${work}/consumer" RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "consumer failed: ${rc}")
endif()
