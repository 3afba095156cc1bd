# Driver of the "add_subdirectory" and "fetch_content" tests (cmake -P): configure and build an
# outside project that takes Penumbra's source tree, with every optional dependency hidden
# (glslang, nlohmann_json, doctest, GLFW: CMAKE_DISABLE_FIND_PACKAGE_*), so that the header-only
# core is shown to need only a C++20 compiler; then run it.
#   -DMODE=add_subdirectory|fetch_content -DSOURCE_DIR -DWORK_DIR -DCMAKE_GENERATOR
#   [-DCXX_COMPILER] [-DLAUNCHER]
include(${CMAKE_CURRENT_LIST_DIR}/../script_steps.cmake)
require_variables(MODE SOURCE_DIR WORK_DIR CMAKE_GENERATOR)
if(NOT MODE MATCHES "^(add_subdirectory|fetch_content)$")
    message(FATAL_ERROR "run.cmake: MODE '${MODE}'; allowed: add_subdirectory, fetch_content")
endif()

file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
set(consumer ${WORK_DIR}/consumer)
set(options -DCMAKE_BUILD_TYPE=Debug)
if(CXX_COMPILER)
    list(APPEND options -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
endif()
if(LAUNCHER)
    list(APPEND options -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
foreach(package IN ITEMS glslang nlohmann_json doctest glfw3 Threads Python3)
    list(APPEND options -DCMAKE_DISABLE_FIND_PACKAGE_${package}=TRUE)
endforeach()

if(MODE STREQUAL "add_subdirectory")
    list(APPEND options -DPENUMBRA_SOURCE_DIR=${SOURCE_DIR})
else()
    # The source tree as a release archive would hold it: the files git knows (tracked, and new
    # ones not ignored), so no build directory comes along; without git, what the library needs.
    find_package(Git QUIET)
    set(result 1)
    if(Git_FOUND)
        execute_process(COMMAND ${GIT_EXECUTABLE} ls-files --cached --others --exclude-standard
            WORKING_DIRECTORY ${SOURCE_DIR} OUTPUT_VARIABLE listed RESULT_VARIABLE result ERROR_QUIET)
        string(REPLACE "\n" ";" listed "${listed}")
    endif()
    if(NOT result EQUAL 0)
        file(GLOB_RECURSE listed RELATIVE ${SOURCE_DIR} ${SOURCE_DIR}/include/* ${SOURCE_DIR}/cmake/*
            ${SOURCE_DIR}/docs/*)
        list(APPEND listed CMakeLists.txt LICENSE README.md)
    endif()
    set(files "")
    foreach(file IN LISTS listed)
        if(file AND EXISTS ${SOURCE_DIR}/${file})
            list(APPEND files "penumbra/${file}")
        endif()
    endforeach()
    file(CREATE_LINK ${SOURCE_DIR} ${WORK_DIR}/penumbra SYMBOLIC)
    set(archive ${WORK_DIR}/penumbra-source.tar.gz)
    string(JOIN "\n" file_list ${files})
    file(WRITE ${WORK_DIR}/files.txt "${file_list}\n")
    step(${CMAKE_COMMAND} -E chdir ${WORK_DIR} ${CMAKE_COMMAND} -E tar czf ${archive} --files-from=files.txt)
    list(APPEND options -DPENUMBRA_ARCHIVE=${archive})
endif()

step(${CMAKE_COMMAND} --no-warn-unused-cli -S ${CMAKE_CURRENT_LIST_DIR}/${MODE} -B ${consumer} -G ${CMAKE_GENERATOR} ${options})
step(${CMAKE_COMMAND} --build ${consumer})
step(${consumer}/app)
message(STATUS "${MODE} consumer built and ran")
