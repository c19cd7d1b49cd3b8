# topkit_warnings(target): the project's warning set, PRIVATE to the target.
function(topkit_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow
    -Wconversion -Wno-sign-conversion -Wno-missing-field-initializers $<$<BOOL:${TOPKIT_WERROR}>:-Werror>)
endfunction()
option(TOPKIT_WERROR "Treat warnings as errors" OFF)
