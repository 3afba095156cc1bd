# Shared by the add_subdirectory and fetch_content consumers: as a subproject, Penumbra builds the
# header-only library and nothing else (no tools, tests, playground, benchmarks, WebAssembly).
function(penumbra_consumer_checks)
    if(NOT TARGET penumbra::penumbra)
        message(FATAL_ERROR "consumer: no penumbra::penumbra target")
    endif()
    foreach(tool IN ITEMS penumbra-gen penumbra-tests-text penumbra-playground penumbra-emitter-wasm penumbra-bench-emit)
        if(TARGET ${tool})
            message(FATAL_ERROR "consumer: Penumbra as a subproject built '${tool}'; only the library is wanted")
        endif()
    endforeach()
endfunction()

# PENUMBRA_CONSUMER_SEPARATE: the emitter compiled once, in implementation.cpp, and only declared in
# main.cpp (PENUMBRA_SEPARATE_IMPLEMENTATION); otherwise header-only.
if(PENUMBRA_CONSUMER_SEPARATE)
    add_executable(app ${CMAKE_CURRENT_LIST_DIR}/main.cpp ${CMAKE_CURRENT_LIST_DIR}/implementation.cpp)
    target_compile_definitions(app PRIVATE PENUMBRA_SEPARATE_IMPLEMENTATION)
else()
    add_executable(app ${CMAKE_CURRENT_LIST_DIR}/main.cpp)
endif()
target_link_libraries(app PRIVATE penumbra::penumbra)
penumbra_consumer_checks()
