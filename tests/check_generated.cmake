# Fails when the output of GEN differs from the committed file DOC.
execute_process(COMMAND ${GEN} OUTPUT_VARIABLE out RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "${GEN} failed: ${rc}")
endif()
file(READ ${DOC} committed)
if(NOT out STREQUAL committed)
  message(FATAL_ERROR "${DOC} is out of date; regenerate it with: ${GEN} > ${DOC}")
endif()
