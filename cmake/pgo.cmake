# Profile-guided optimisation of the protocol library and topdump (GCC).
#
# With TOPKIT_PGO (on in the default preset), the build first builds an
# instrumented topdump and gen_capture in ${CMAKE_BINARY_DIR}/pgo/gen (a
# nested build of this same source tree), runs them on a training set
# (cmake/pgo-train.cmake: generated UDP and TCP captures and a serial dump,
# and every bundled capture, through read, read -V, read --json, read --csv,
# stats and report), and then compiles the library, topdump's libraries and topdump with
# the profile. Everything else builds as usual. The training captures are
# not the benchmark's (other seeds and sizes); bench/README.md gives the
# figures with and without the profile.
#
# Object files of both builds sit at the same paths relative to their build
# directories, and -fprofile-prefix-path strips those directories, so the
# final build finds each object's profile. A function not run in training
# is optimised as without a profile (-fprofile-partial-training), and so is
# a whole file none of whose code runs there (encode.cpp: topdump never
# encodes), which has no profile at all (-Wno-missing-profile).
option(TOPKIT_PGO "Build the library and topdump with profile-guided optimisation (GCC)" OFF)

set(TOPKIT_PGO_ACTIVE OFF)
if(TOPKIT_PGO)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    message(WARNING "TOPKIT_PGO needs GCC (have ${CMAKE_CXX_COMPILER_ID}); building without it")
  elseif(CMAKE_BUILD_TYPE STREQUAL "Debug")
    message(WARNING "TOPKIT_PGO is for optimised builds; building without it")
  elseif(NOT TOPKIT_TOOLS)
    message(WARNING "TOPKIT_PGO trains with topdump (TOPKIT_TOOLS); building without it")
  else()
    set(TOPKIT_PGO_ACTIVE ON)
  endif()
endif()

if(TOPKIT_PGO_ACTIVE)
  include(ExternalProject)
  set(TOPKIT_PGO_GEN ${CMAKE_BINARY_DIR}/pgo/gen)    # the instrumented build
  set(TOPKIT_PGO_DATA ${CMAKE_BINARY_DIR}/pgo/data)  # its profiles (*.gcda)
  set(TOPKIT_PGO_STAMP ${CMAKE_BINARY_DIR}/pgo/trained.stamp)
  set(topkit_pgo_exe_suffix ${CMAKE_EXECUTABLE_SUFFIX})
  # the instrumented build compiles as this one does (the default preset's
  # -g1 too), so each object's profile matches it
  string(TOUPPER "${CMAKE_BUILD_TYPE}" topkit_pgo_config)
  ExternalProject_Add(topkit_pgo_instrumented
    SOURCE_DIR ${PROJECT_SOURCE_DIR}
    BINARY_DIR ${TOPKIT_PGO_GEN}
    CMAKE_ARGS
      -DCMAKE_BUILD_TYPE=${CMAKE_BUILD_TYPE}
      "-DCMAKE_CXX_FLAGS_${topkit_pgo_config}=${CMAKE_CXX_FLAGS_${topkit_pgo_config}}"
      -DCMAKE_CXX_COMPILER=${CMAKE_CXX_COMPILER}
      "-DCMAKE_CXX_FLAGS=${CMAKE_CXX_FLAGS} -fprofile-generate=${TOPKIT_PGO_DATA} -fprofile-prefix-path=${TOPKIT_PGO_GEN} -fprofile-update=single"
      "-DCMAKE_EXE_LINKER_FLAGS=${CMAKE_EXE_LINKER_FLAGS} -fprofile-generate"
      -DTOPKIT_PGO=OFF -DTOPKIT_TESTS=OFF -DTOPKIT_BENCH=OFF -DTOPKIT_WERROR=OFF
    BUILD_COMMAND ${CMAKE_COMMAND} --build <BINARY_DIR> --target topdump gen_capture
    BUILD_ALWAYS ON
    BUILD_BYPRODUCTS
      ${TOPKIT_PGO_GEN}/analyzer/topdump${topkit_pgo_exe_suffix}
      ${TOPKIT_PGO_GEN}/analyzer/gen_capture${topkit_pgo_exe_suffix}
    INSTALL_COMMAND ""
    TEST_COMMAND "")
  file(GLOB topkit_pgo_captures CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/captures/*.pcap
       ${PROJECT_SOURCE_DIR}/captures/*.pcapng ${PROJECT_SOURCE_DIR}/captures/*.log
       ${PROJECT_SOURCE_DIR}/captures/*.csv ${PROJECT_SOURCE_DIR}/captures/*.bin)
  add_custom_command(OUTPUT ${TOPKIT_PGO_STAMP}
    COMMAND ${CMAKE_COMMAND}
      -DTOPDUMP=${TOPKIT_PGO_GEN}/analyzer/topdump${topkit_pgo_exe_suffix}
      -DGEN=${TOPKIT_PGO_GEN}/analyzer/gen_capture${topkit_pgo_exe_suffix}
      -DDATA=${TOPKIT_PGO_DATA} -DWORK=${CMAKE_BINARY_DIR}/pgo/work
      -DCAPTURES=${PROJECT_SOURCE_DIR}/captures -DSTAMP=${TOPKIT_PGO_STAMP}
      -P ${PROJECT_SOURCE_DIR}/cmake/pgo-train.cmake
    DEPENDS
      ${TOPKIT_PGO_GEN}/analyzer/topdump${topkit_pgo_exe_suffix}
      ${TOPKIT_PGO_GEN}/analyzer/gen_capture${topkit_pgo_exe_suffix}
      ${PROJECT_SOURCE_DIR}/cmake/pgo-train.cmake ${topkit_pgo_captures}
    COMMENT "PGO: training the instrumented topdump"
    VERBATIM)
  add_custom_target(topkit_pgo_profile DEPENDS ${TOPKIT_PGO_STAMP})
  add_dependencies(topkit_pgo_profile topkit_pgo_instrumented)
endif()

# The targets built with the profile call topkit_optimise (cmake/codegen.cmake).
