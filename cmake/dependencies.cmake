# Every third-party dependency, found once, here (all Debian 12 packages:
# scripts/install-deps.sh installs them). The library (protocol/) needs
# none; the tools, tests, fuzz targets and benchmarks find what they use.
# Imported targets found here are seen by every folder below.
if(TOPKIT_TOOLS OR TOPKIT_TESTS)
  find_package(CLI11 REQUIRED)          # the tools' command lines (tools/cli)
  find_package(Threads REQUIRED)
endif()
if(TOPKIT_TOOLS OR TOPKIT_TESTS OR TOPKIT_FUZZ)
  find_package(nlohmann_json 3 REQUIRED)  # matrices, reports, JSON checks
endif()
if(TOPKIT_TOOLS)
  include(${CMAKE_CURRENT_LIST_DIR}/pcap.cmake)    # libpcap (topkit::pcap)
  find_package(spdlog REQUIRED)                     # topsim and topconf logs
  find_path(TOPKIT_ASIO_INCLUDE asio.hpp REQUIRED)  # standalone Asio
endif()
if(TOPKIT_TESTS)
  find_package(GTest REQUIRED)
  find_package(Python3 COMPONENTS Interpreter)  # lints and report checks; skipped without
endif()
if(TOPKIT_BENCH)
  find_package(benchmark REQUIRED)  # Google Benchmark
endif()
