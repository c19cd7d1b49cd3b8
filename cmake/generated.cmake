# Every file of the source tree that a tool writes, in one table:
#   cmake --build BUILD --target regenerate    writes them all again
#   ctest -L generated                         fails on any that is stale
# Review the diff after regenerating. Each entry names the generator and the
# file it writes; the test runs the generator into the build tree and
# compares byte for byte (tests/check_generated.cmake).
#
# topkit_generated(NAME name OUTPUT file COMMAND exe [args...])
#   the generator writes the file to its standard output
# topkit_generated(NAME name DIRECTORY dir COMMAND exe [args...])
#   the generator writes into the directory given as its last argument; every
#   file it writes must equal the committed one
add_custom_target(regenerate)

function(topkit_generated)
  cmake_parse_arguments(G "" "NAME;OUTPUT;DIRECTORY;LABELS" "COMMAND" ${ARGN})
  set(labels generated ${G_LABELS})
  if(G_OUTPUT)
    add_custom_command(TARGET regenerate POST_BUILD
      COMMAND ${G_COMMAND} > ${PROJECT_SOURCE_DIR}/${G_OUTPUT}
      COMMENT "regenerate ${G_OUTPUT}" VERBATIM)
    list(POP_FRONT G_COMMAND gen)
    add_test(NAME generated.${G_NAME}
      COMMAND ${CMAKE_COMMAND} -DGEN=${gen} "-DARGS=${G_COMMAND}"
              -DDOC=${PROJECT_SOURCE_DIR}/${G_OUTPUT}
              -P ${PROJECT_SOURCE_DIR}/tests/check_generated.cmake)
  else()
    add_custom_command(TARGET regenerate POST_BUILD
      COMMAND ${G_COMMAND} ${PROJECT_SOURCE_DIR}/${G_DIRECTORY}
      COMMENT "regenerate ${G_DIRECTORY}/" VERBATIM)
    list(POP_FRONT G_COMMAND gen)
    add_test(NAME generated.${G_NAME}
      COMMAND ${CMAKE_COMMAND} -DGEN=${gen} "-DARGS=${G_COMMAND}"
              -DDIR=${PROJECT_SOURCE_DIR}/${G_DIRECTORY}
              -DOUT=${PROJECT_BINARY_DIR}/generated/${G_NAME}
              -P ${PROJECT_SOURCE_DIR}/tests/check_generated.cmake)
  endif()
  set_tests_properties(generated.${G_NAME} PROPERTIES LABELS "${labels}")
endfunction()

topkit_generated(NAME catalog_md OUTPUT docs/CATALOG.md COMMAND $<TARGET_FILE:catalog_md>
  LABELS docs)
topkit_generated(NAME field_md OUTPUT docs/FIELD.md COMMAND $<TARGET_FILE:field_md> LABELS docs)
topkit_generated(NAME diagnoses_md OUTPUT docs/DIAGNOSES.md COMMAND $<TARGET_FILE:diagnoses_md>
  LABELS docs)
add_dependencies(regenerate catalog_md field_md diagnoses_md)

if(TOPKIT_TOOLS)
  # The default matrices, one per model (conformance/matrices/regenerate.sh
  # also rewrites the schema's model list).
  foreach(model c10 c10pro c12 c13 c20 sip)
    topkit_generated(NAME matrix_${model} OUTPUT conformance/matrices/${model}.json
      COMMAND $<TARGET_FILE:topconf> generate --model ${model} LABELS conformance)
  endforeach()
  # The synthetic captures (captures/README.md says which; the recorded
  # loopback-real.pcap is not one of them).
  topkit_generated(NAME captures DIRECTORY captures COMMAND $<TARGET_FILE:make_captures>
    LABELS analyzer)
  add_dependencies(regenerate topdump topconf make_captures)
endif()
