# lint.clang_tidy: clang-tidy over the library's sources with the build's
# compile commands, less GCC's profile options and -Wno-missing-profile
# (cmake/pgo.cmake), which clang does not know.
#   cmake -DTIDY=... -DBINARY_DIR=... -DSOURCE_DIR=... -P clang_tidy.cmake
file(READ ${BINARY_DIR}/compile_commands.json db)
string(REGEX REPLACE " -fprofile-[^ \"]*" "" db "${db}")
string(REPLACE " -Wno-missing-profile" "" db "${db}")
set(dir ${BINARY_DIR}/lint)
file(MAKE_DIRECTORY ${dir})
file(WRITE ${dir}/compile_commands.json "${db}")
file(GLOB sources ${SOURCE_DIR}/protocol/src/*.cpp)
execute_process(COMMAND ${TIDY} -p ${dir} --quiet ${sources} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "clang-tidy: ${rc}")
endif()
