# Code layout for speed (GCC, optimised builds): topdump's per-frame path
# (capture reader, session, decode, diagnoses) is larger than a core's
# 32 KB instruction cache, so what costs time is instruction fetch, not
# instructions (measured: docs/perf/decisions.md, "No alignment padding,
# no PLT"):
#
# - no alignment padding of functions, loops, jumps and labels: the code
#   that runs is denser;
# - calls into shared libraries (libc's fread, memcmp, malloc) through the
#   GOT instead of PLT stubs, which take cache lines of their own
#   (-fno-plt). Symbols then bind when the program loads, not at their
#   first call.
#
# Every target takes them (the PGO instrumented build too: it configures
# this same tree). Clang warns on some of the alignment flags, so GCC only.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  add_compile_options(
    "$<$<NOT:$<CONFIG:Debug>>:-falign-functions=1;-falign-jumps=1;-falign-loops=1;-falign-labels=1>"
    "$<$<NOT:$<CONFIG:Debug>>:-fno-plt>")
endif()

# Link-time optimisation of topdump (TOPKIT_LTO, on in the default preset;
# GCC, optimised builds): its library sources are compiled once, into fat
# objects (GIMPLE and machine code), so only topdump's own link reads the
# GIMPLE and optimises across the rooms (inlining the protocol's lookups
# into the session's per-frame path), while tests and tools link the
# machine code as before (measured: docs/perf/decisions.md, "Link-time
# optimisation of topdump").
# GCC 12 warns at that link of string concatenations it inlines
# (-Wstringop-overflow, a false positive of std::string's operator+).
option(TOPKIT_LTO "Link topdump with link-time optimisation (GCC)" OFF)
set(TOPKIT_LTO_ACTIVE OFF)
if(TOPKIT_LTO AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND NOT CMAKE_BUILD_TYPE STREQUAL "Debug")
  set(TOPKIT_LTO_ACTIVE ON)
endif()
# topkit_optimise(target): a target topdump's speed rests on (the library,
# topdump's rooms, topdump itself; call it where the target is defined)
# takes both optimisations that are on: the PGO profile (cmake/pgo.cmake),
# its sources compiled again whenever it is retrained, and LTO, fat
# objects, with topdump's own link reading their GIMPLE.
function(topkit_optimise target)
  if(TOPKIT_PGO_ACTIVE OR TOPKIT_LTO_ACTIVE)
    # its objects as measured and profiled, one a source (TOPKIT_UNITY)
    set_target_properties(${target} PROPERTIES UNITY_BUILD OFF)
  endif()
  if(TOPKIT_PGO_ACTIVE)
    target_compile_options(${target} PRIVATE -fprofile-use=${TOPKIT_PGO_DATA}
      -fprofile-prefix-path=${CMAKE_BINARY_DIR} -fprofile-partial-training -Wno-missing-profile)
    add_dependencies(${target} topkit_pgo_profile)
    get_target_property(sources ${target} SOURCES)
    set_source_files_properties(${sources} PROPERTIES OBJECT_DEPENDS ${TOPKIT_PGO_STAMP})
  endif()
  if(TOPKIT_LTO_ACTIVE)
    target_compile_options(${target} PRIVATE -flto=auto -ffat-lto-objects)
    get_target_property(type ${target} TYPE)
    if(type STREQUAL "EXECUTABLE")
      target_link_options(${target} PRIVATE -flto=auto -Wno-stringop-overflow)
    endif()
  endif()
endfunction()

# Unity builds (TOPKIT_UNITY, on in the default and asan presets): a
# target's sources compile in batches of 8, one compiler run a batch, so
# the heavy headers (nlohmann::json, CLI11, GoogleTest, Asio) are parsed
# and their templates instantiated once a batch instead of once a file.
# Build time only, for CI's 30 minutes: the asan build took 665 s of
# 2 cores, 4/5 of it the tests, front ends and conformance rooms. Not the
# targets topdump's speed rests on while PGO or LTO is on (topkit_optimise
# keeps their objects one a source, as profiled and measured), nor the fuzz
# builds (off by default: their instruction budgets, fuzz/guard.sh, are of
# objects one a source).
option(TOPKIT_UNITY "Compile each target's sources in unity batches (build time)" OFF)
set(CMAKE_UNITY_BUILD ${TOPKIT_UNITY})
set(CMAKE_UNITY_BUILD_BATCH_SIZE 8)

# topkit_quick_compile(target): code whose speed never matters, only its build
# time: the test drivers (tests/), and with TOPKIT_QUICK_FRONTENDS (on
# in the asan preset) the command-line front ends too. They compile at -Og
# in every configuration (after the configuration's -O, so it wins); the
# code they test and call (protocol/, the rooms, the simulator, the runner)
# keeps the configuration's optimisation. Never on a target topdump's speed
# rests. -Og, not -O0: the linker keeps the first copy of an inline
# function (std::string's, nlohmann::json's, our headers'), which is the
# test's, so the library under test runs it too, much slower at -O0
# (measured: docs/perf/decisions.md, "Test drivers and front ends at -Og").
option(TOPKIT_QUICK_FRONTENDS
  "Compile the command-line front ends (topdump_cli, topsim, topconf) at -Og" OFF)
function(topkit_quick_compile target)
  target_compile_options(${target} PRIVATE -Og)
endfunction()
function(topkit_quick_frontend target)
  if(TOPKIT_QUICK_FRONTENDS)
    topkit_quick_compile(${target})
  endif()
endfunction()
