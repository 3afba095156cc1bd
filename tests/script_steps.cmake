# Shared by the cmake -P drivers of the package tests (find_package/run.cmake, consumer/run.cmake).

# Stops with a message naming the first of the listed variables that is not set.
function(require_variables)
    foreach(var IN LISTS ARGN)
        if(NOT ${var})
            message(FATAL_ERROR "${CMAKE_CURRENT_LIST_FILE}: ${var} not set")
        endif()
    endforeach()
endfunction()

# Runs a command; stops with its exit status and command line when it fails.
function(step)
    execute_process(COMMAND ${ARGN} RESULT_VARIABLE result)
    if(NOT result EQUAL 0)
        string(JOIN " " line ${ARGN})
        message(FATAL_ERROR "failed (${result}): ${line}")
    endif()
endfunction()
