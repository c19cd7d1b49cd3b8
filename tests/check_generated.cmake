# Fails when the output of GEN (run with the arguments ARGS, if any) differs
# from the committed file DOC.
execute_process(COMMAND ${GEN} ${ARGS} OUTPUT_VARIABLE out RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "${GEN} failed: ${rc}")
endif()
file(READ ${DOC} committed)
if(NOT out STREQUAL committed)
  message(FATAL_ERROR "${DOC} is out of date; regenerate it with: ${GEN} ${ARGS} > ${DOC}")
endif()
