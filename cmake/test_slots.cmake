# Cores for ctest: CI's test passes (the test presets in CMakePresets.json)
# run ctest with six jobs and the resource spec tests/cpu-slots.json, which
# has two "cpu" slots, one per core of the CI machine. Every test takes one
# (RESOURCE_GROUPS cpu:1), so no more than two of them run at a time, as
# with -j2; but the tests that mostly wait on real time (topsim and a client
# over real UDP, TCP or a pty for seconds, at about 1% of a core: the WAITS
# executables of tests/conformance/, 177 s of waiting per pass for 1.5 s of
# CPU) take none, so up to four of them wait beside the two that work.
# driver_client_tests is not one (tests/conformance/CMakeLists.txt says
# why). report.chromium runs two browsers and takes both slots. Without the spec file (a plain `ctest -j2`)
# ctest ignores the slots and runs the tests as before.
#
# topkit_tests_take_a_core(): every test of the calling directory without
# RESOURCE_GROUPS takes a slot; each directory that adds tests defers a call
# to it (cmake_language(DEFER CALL ...)), so a test added later is covered.
function(topkit_tests_take_a_core)
  get_property(tests DIRECTORY PROPERTY TESTS)
  foreach(t IN LISTS tests)
    get_test_property(${t} RESOURCE_GROUPS groups)
    if(NOT groups)
      set_tests_properties(${t} PROPERTIES RESOURCE_GROUPS cpu:1)
    endif()
  endforeach()
endfunction()
