# topconf_matrix: the matrix model, loader and generator (what the matrix
# fuzz target links). Pure: no I/O, no Asio.
topkit_room(topconf_matrix DIR ${CMAKE_CURRENT_LIST_DIR}
  SOURCES matrix.cpp matrix_expect.cpp generate.cpp
  LINKS topkit::protocol topsim_core nlohmann_json::nlohmann_json)
