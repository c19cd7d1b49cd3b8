# build.cxx_standard: every compile command of the build asks for C++20.
# A target that does not link the library (which asks for it) once compiled
# with the compiler's default, and clang's (C++14) has no std::string_view.
#   cmake -DBINARY_DIR=... -P check_std.cmake
file(READ ${BINARY_DIR}/compile_commands.json db)
string(JSON count LENGTH "${db}")
math(EXPR last "${count} - 1")
set(missing "")
foreach(i RANGE ${last})
  string(JSON command GET "${db}" ${i} command)
  string(JSON file GET "${db}" ${i} file)
  if(NOT command MATCHES " -std=(gnu|c)\\+\\+(20|2a) ")
    list(APPEND missing ${file})
  endif()
endforeach()
if(missing)
  list(JOIN missing "\n  " text)
  message(FATAL_ERROR "compiled without -std=c++20 / gnu++20:\n  ${text}")
endif()
message(STATUS "${count} compile commands, all C++20")
