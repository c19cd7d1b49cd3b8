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
