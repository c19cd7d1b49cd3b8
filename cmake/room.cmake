# topkit_room(name DIR dir SOURCES file... [LINKS lib...] [PRIVATE_LINKS lib...] [OPTIMISED])
#
# One room of the tree as a static library, the one way every library room
# is built: dir/include/ is its face (PUBLIC: the headers other rooms and
# the tests include, as "room/header.hpp"), dir/src/ holds its sources and
# private headers (PRIVATE, included by their bare name). SOURCES are file
# names in dir/src/ (an absolute path is taken as it is: a generated file).
# LINKS are public (a room's headers include its dependencies'). OPTIMISED:
# the profile-guided and link-time optimisation topdump's rooms get
# (cmake/pgo.cmake, cmake/codegen.cmake).
function(topkit_room name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "OPTIMISED" "DIR" "SOURCES;LINKS;PRIVATE_LINKS")
  get_filename_component(dir "${arg_DIR}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  set(sources "")
  foreach(s IN LISTS arg_SOURCES)
    if(IS_ABSOLUTE "${s}")
      list(APPEND sources "${s}")
    else()
      list(APPEND sources "${dir}/src/${s}")
    endif()
  endforeach()
  add_library(${name} STATIC ${sources})
  if(EXISTS "${dir}/include")
    target_include_directories(${name} PUBLIC "${dir}/include")
  endif()
  target_include_directories(${name} PRIVATE "${dir}/src")
  target_link_libraries(${name} PUBLIC ${arg_LINKS} PRIVATE ${arg_PRIVATE_LINKS})
  target_compile_features(${name} PUBLIC cxx_std_20)
  topkit_warnings(${name})
  if(arg_OPTIMISED)
    topkit_optimise(${name})
  endif()
endfunction()
