# The pure libraries of conformance/ (no I/O, no Asio): the device model
# with fault injection and the device rules (sim/), and the matrix loader
# and generator (conf/matrix/). conformance/CMakeLists.txt includes this;
# fuzz/CMakeLists.txt can include it too when the tools are off (the fuzz
# preset):
#   include(${PROJECT_SOURCE_DIR}/conformance/libs.cmake)
# Entry points: topsim::handle_datagram (sim/intake.hpp, topsim_core) and
# topconf::load_matrix (conf/matrix.hpp, topconf_matrix).
if(NOT TARGET topsim_core)
  include(${CMAKE_CURRENT_LIST_DIR}/sim/libs.cmake)
  include(${CMAKE_CURRENT_LIST_DIR}/conf/matrix/libs.cmake)
endif()
