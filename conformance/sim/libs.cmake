# topsim_core: device model, device rules, fault injection and the intake
# (bytes -> frames -> admitted -> handled). Pure: no I/O, no clock.
topkit_room(topsim_core DIR ${CMAKE_CURRENT_LIST_DIR}
  SOURCES device.cpp device_describe.cpp device_handlers.cpp device_topotek.cpp
          device_faults.cpp fanout.cpp faults.cpp firmware_faults.cpp intake.cpp
  LINKS topkit::protocol)
