# The pure libraries of conformance/ (no I/O, no Asio): the device model
# with fault injection, and the matrix loader. conformance/CMakeLists.txt
# includes this; fuzz/CMakeLists.txt can include it too when the tools are
# off (the fuzz preset):
#   include(${PROJECT_SOURCE_DIR}/conformance/libs.cmake)
# Entry points: topsim::handle_datagram (sim/device.hpp, topsim_core) and
# topconf::load_matrix (conf/matrix.hpp, topconf_matrix).
if(NOT TARGET topsim_core)
  find_package(nlohmann_json 3 REQUIRED)
  set(_topkit_conf ${CMAKE_CURRENT_LIST_DIR})

# Device model and fault injection: pure, fuzzable.
add_library(topsim_core STATIC ${_topkit_conf}/sim/src/device.cpp ${_topkit_conf}/sim/src/faults.cpp
  ${_topkit_conf}/sim/src/firmware_faults.cpp)
target_include_directories(topsim_core PUBLIC ${_topkit_conf}/sim/include)
target_link_libraries(topsim_core PUBLIC topkit::protocol)
target_compile_features(topsim_core PUBLIC cxx_std_20)
topkit_warnings(topsim_core)

# The matrix loader alone (no I/O, no Asio): what the fuzz target links.
add_library(topconf_matrix STATIC ${_topkit_conf}/conf/matrix/src/matrix.cpp)
target_include_directories(topconf_matrix PUBLIC ${_topkit_conf}/conf/matrix/include)
target_link_libraries(topconf_matrix PUBLIC topkit::protocol nlohmann_json::nlohmann_json)
target_compile_features(topconf_matrix PUBLIC cxx_std_20)
topkit_warnings(topconf_matrix)

endif()
