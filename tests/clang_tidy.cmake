# lint.clang_tidy.*: clang-tidy over the library's sources with the build's
# compile commands, less GCC's profile options and -Wno-missing-profile
# (cmake/pgo.cmake) and its code-layout options (cmake/codegen.cmake), which
# clang does not know. lint.clang_tidy_db writes
# those commands (a fixture); then one test per source file, so that ctest
# spreads the files over the cores (one run over them all took 200 s of one
# core while the other ran the rest).
#   cmake -DBINARY_DIR=... -DWRITE_DB=ON -P clang_tidy.cmake
#   cmake -DTIDY=... -DBINARY_DIR=... -DSOURCES=file.cpp[;...] -P clang_tidy.cmake
set(dir ${BINARY_DIR}/lint)
if(WRITE_DB)
  file(READ ${BINARY_DIR}/compile_commands.json db)
  string(REGEX REPLACE " -fprofile-[^ \"]*" "" db "${db}")
  string(REPLACE " -Wno-missing-profile" "" db "${db}")
  string(REGEX REPLACE " -falign-[a-z]+=[0-9]+" "" db "${db}")
  string(REPLACE " -flto=auto -ffat-lto-objects" "" db "${db}")
  file(MAKE_DIRECTORY ${dir})
  file(WRITE ${dir}/compile_commands.json "${db}")
  return()
endif()
if(NOT SOURCES)
  message(FATAL_ERROR "clang_tidy.cmake: no SOURCES")
endif()
execute_process(COMMAND ${TIDY} -p ${dir} --quiet ${SOURCES} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "clang-tidy: ${rc}")
endif()
