# topsim_core: device model, device rules, fault injection and the intake
# (bytes -> frames -> admitted -> handled). Pure: no I/O, no clock.
set(_topkit_sim ${CMAKE_CURRENT_LIST_DIR})
add_library(topsim_core STATIC
  ${_topkit_sim}/src/device.cpp
  ${_topkit_sim}/src/device_describe.cpp
  ${_topkit_sim}/src/device_handlers.cpp
  ${_topkit_sim}/src/device_topotek.cpp
  ${_topkit_sim}/src/device_faults.cpp
  ${_topkit_sim}/src/fanout.cpp
  ${_topkit_sim}/src/faults.cpp
  ${_topkit_sim}/src/firmware_faults.cpp
  ${_topkit_sim}/src/intake.cpp)
target_include_directories(topsim_core PUBLIC ${_topkit_sim}/include PRIVATE ${_topkit_sim}/src)
target_link_libraries(topsim_core PUBLIC topkit::protocol)
target_compile_features(topsim_core PUBLIC cxx_std_20)
topkit_warnings(topsim_core)
