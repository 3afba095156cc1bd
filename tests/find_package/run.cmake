# Driver of the "find_package" test (cmake -P): install the build tree into a fresh prefix,
# configure and build tests/find_package against it, check that the shaders were generated.
#   -DBUILD_DIR -DCONFIG -DCONSUMER_SOURCE_DIR -DWORK_DIR -DCMAKE_GENERATOR -DCXX_COMPILER
include(${CMAKE_CURRENT_LIST_DIR}/../script_steps.cmake)
require_variables(BUILD_DIR CONSUMER_SOURCE_DIR WORK_DIR CMAKE_GENERATOR)
if(NOT CONFIG)
    set(CONFIG Release)
endif()

set(prefix ${WORK_DIR}/prefix)
set(consumer ${WORK_DIR}/consumer)
file(REMOVE_RECURSE ${WORK_DIR})

step(${CMAKE_COMMAND} --install ${BUILD_DIR} --config ${CONFIG} --prefix ${prefix})
set(compiler "")
if(CXX_COMPILER)
    set(compiler -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
endif()
step(${CMAKE_COMMAND} -S ${CONSUMER_SOURCE_DIR} -B ${consumer} -G ${CMAKE_GENERATOR}
     -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=${CONFIG} ${compiler})
step(${CMAKE_COMMAND} --build ${consumer} --config ${CONFIG})

file(STRINGS ${consumer}/generated_files.txt generated)
foreach(file IN LISTS generated)
    if(NOT EXISTS ${file})
        message(FATAL_ERROR "penumbra_generate_shaders declared ${file}, which the build did not write")
    endif()
endforeach()
step(${consumer}/app)
list(LENGTH generated count)
message(STATUS "find_package consumer built and ran; the ${count} generated files it declared exist")
