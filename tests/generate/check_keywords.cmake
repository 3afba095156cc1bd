# The "generate_keywords" test (cmake -P): penumbra_generate_shaders has a keyword for every flag
# penumbra-gen accepts, and no keyword for a flag it does not. The generator's own list is the one
# its "unknown flag" message prints.
#   -DGENERATOR=<penumbra-gen> -DMODULE=<cmake/PenumbraGenerate.cmake>
cmake_minimum_required(VERSION 3.25)
include(${MODULE})
penumbra_generate_flags(value_flags switch_flags)
set(ours ${value_flags} ${switch_flags})

execute_process(COMMAND ${GENERATOR} --no-such-flag RESULT_VARIABLE result ERROR_VARIABLE message OUTPUT_QUIET)
if(NOT message MATCHES "allowed: ([^\n]*)")
    message(FATAL_ERROR "penumbra-gen --no-such-flag printed no list of flags: ${message}")
endif()
string(REPLACE ", " ";" theirs "${CMAKE_MATCH_1}")
# Flags with a keyword of their own or none: --config is CONFIG, --out is OUT_DIR, --help is not one.
list(REMOVE_ITEM theirs --config --out --help)

set(missing "")
foreach(flag IN LISTS theirs)
    if(NOT flag IN_LIST ours)
        list(APPEND missing ${flag})
    endif()
endforeach()
set(extra "")
foreach(flag IN LISTS ours)
    if(NOT flag IN_LIST theirs)
        list(APPEND extra ${flag})
    endif()
endforeach()
if(missing OR extra)
    message(FATAL_ERROR "penumbra_generate_flags() and penumbra-gen differ: no keyword for [${missing}]; "
        "keywords for flags penumbra-gen does not take: [${extra}]")
endif()
list(LENGTH ours count)
message(STATUS "${count} flags, each with a keyword")
