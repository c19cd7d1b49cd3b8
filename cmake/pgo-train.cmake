# The PGO training run (cmake/pgo.cmake): the instrumented topdump on a
# generated capture and on every bundled capture, through each output.
#   cmake -DTOPDUMP=... -DGEN=... -DDATA=... -DWORK=... -DCAPTURES=... -DSTAMP=...
#         -P pgo-train.cmake
foreach(var TOPDUMP GEN DATA WORK CAPTURES STAMP)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "pgo-train: ${var} not set")
  endif()
endforeach()

# A fresh profile: gcda files add up over runs.
file(REMOVE_RECURSE ${DATA} ${WORK})
file(MAKE_DIRECTORY ${WORK})

# Runs a tool; exit statuses 0 and 1 are verdicts (1: a finding is an
# error). Anything else stops the build: 2 (bad usage or unreadable input)
# would otherwise leave that path out of the profile without a word, and a
# crash is a crash.
function(train)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
  if(NOT rc MATCHES "^[01]$")
    list(JOIN ARGN " " cmd)
    message(FATAL_ERROR "pgo-train: ${cmd}: ${rc}")
  endif()
endfunction()

# The generator's mix (bench/README.md) with another seed and size than the
# benchmark's capture.
set(capture ${WORK}/train.pcap)
train(${GEN} 200000 ${capture} 7)
train(${TOPDUMP} stats ${capture})
train(${TOPDUMP} stats --json ${capture})
train(${TOPDUMP} read --json --no-progress ${capture})
train(${TOPDUMP} report ${capture} -o ${WORK}/train.html)
# The same traffic over TCP (reassembly) and as a raw serial dump (the
# stream decoder), in a volume that keeps those paths as hot in the profile
# as they are in use.
set(tcp ${WORK}/train-tcp.pcap)
train(${GEN} 100000 ${tcp} 9 tcp)
train(${TOPDUMP} stats ${tcp})
train(${TOPDUMP} read --json --no-progress ${tcp})
set(serial ${WORK}/train-serial.bin)
train(${GEN} 100000 ${serial} 13 serial)
train(${TOPDUMP} stats --format raw ${serial})
train(${TOPDUMP} read --json --no-progress --format raw ${serial})
set(small ${WORK}/small.pcap)
train(${GEN} 20000 ${small} 11)
train(${TOPDUMP} read --no-progress ${small})
train(${TOPDUMP} read -V --no-progress ${small})
train(${TOPDUMP} read --no-progress --csv time,ident,src,dst,summary ${small})

file(GLOB bundled ${CAPTURES}/*.pcap ${CAPTURES}/*.pcapng ${CAPTURES}/*.log ${CAPTURES}/*.csv
     ${CAPTURES}/*.bin)
foreach(f IN LISTS bundled)
  train(${TOPDUMP} read --no-progress ${f})
  train(${TOPDUMP} read -V --no-progress ${f})
  train(${TOPDUMP} read --json --no-progress ${f})
  train(${TOPDUMP} stats --json ${f})
endforeach()

file(REMOVE_RECURSE ${WORK})
file(TOUCH ${STAMP})
