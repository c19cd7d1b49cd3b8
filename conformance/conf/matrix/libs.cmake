# topconf_matrix: the matrix model, loader and generator (what the matrix
# fuzz target links). Pure: no I/O, no Asio.
set(_topkit_matrix ${CMAKE_CURRENT_LIST_DIR})
add_library(topconf_matrix STATIC
  ${_topkit_matrix}/src/matrix.cpp
  ${_topkit_matrix}/src/matrix_expect.cpp
  ${_topkit_matrix}/src/generate.cpp)
target_include_directories(topconf_matrix PUBLIC ${_topkit_matrix}/include
                           PRIVATE ${_topkit_matrix}/src)
target_link_libraries(topconf_matrix PUBLIC topkit::protocol topsim_core
                      nlohmann_json::nlohmann_json)
target_compile_features(topconf_matrix PUBLIC cxx_std_20)
topkit_warnings(topconf_matrix)
