# penumbra_playground_window: the interactive window (GLFW, Dear ImGui, hot reload).
# Included from playground/CMakeLists.txt; defines the library linked into penumbra-playground.
find_package(glfw3 3.3 REQUIRED) # Debian's target is `glfw`
pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui) # libimgui.a + headers (Debian libimgui-dev)

# Debian ships the GLFW and OpenGL3 backends as sources only: compile them into this library.
set(PENUMBRA_IMGUI_BACKENDS /usr/share/doc/libimgui-dev/examples/backends CACHE PATH
    "folder with imgui_impl_glfw.cpp and imgui_impl_opengl3.cpp")
foreach(backend IN ITEMS imgui_impl_glfw.cpp imgui_impl_opengl3.cpp)
    if(NOT EXISTS ${PENUMBRA_IMGUI_BACKENDS}/${backend})
        message(FATAL_ERROR "penumbra: ${backend} not found in PENUMBRA_IMGUI_BACKENDS=${PENUMBRA_IMGUI_BACKENDS} "
                            "(Debian: apt-get install libimgui-dev)")
    endif()
endforeach()
add_library(penumbra_imgui_backends STATIC
    ${PENUMBRA_IMGUI_BACKENDS}/imgui_impl_glfw.cpp
    ${PENUMBRA_IMGUI_BACKENDS}/imgui_impl_opengl3.cpp)
# imgui_impl_opengl3.cpp includes "imgui_impl_opengl3_loader.h", which Debian puts in backends/.
list(TRANSFORM IMGUI_INCLUDE_DIRS APPEND /backends OUTPUT_VARIABLE imgui_backend_dirs)
target_include_directories(penumbra_imgui_backends PUBLIC ${imgui_backend_dirs})
target_link_libraries(penumbra_imgui_backends PUBLIC PkgConfig::IMGUI glfw ${CMAKE_DL_LIBS})

# The window's logic without GLFW (script, shader folder, diagnostics, statistics): also linked
# by the tests in tests/window/.
add_library(penumbra_playground_window_core STATIC
    ${CMAKE_CURRENT_LIST_DIR}/script.cpp
    ${CMAKE_CURRENT_LIST_DIR}/shader_folder.cpp
    ${CMAKE_CURRENT_LIST_DIR}/shader_diagnostics.cpp
    ${CMAKE_CURRENT_LIST_DIR}/frame_stats.cpp)
target_include_directories(penumbra_playground_window_core PUBLIC ${CMAKE_CURRENT_LIST_DIR})
target_link_libraries(penumbra_playground_window_core PUBLIC penumbra_playground_core)

add_library(penumbra_playground_window STATIC
    ${CMAKE_CURRENT_LIST_DIR}/app.cpp
    ${CMAKE_CURRENT_LIST_DIR}/window_app.cpp
    ${CMAKE_CURRENT_LIST_DIR}/panel.cpp
    ${CMAKE_CURRENT_LIST_DIR}/script_runner.cpp
    ${CMAKE_CURRENT_LIST_DIR}/shader_session.cpp
    ${CMAKE_CURRENT_LIST_DIR}/frame_renderer.cpp)
target_link_libraries(penumbra_playground_window
    PUBLIC penumbra_playground_headless penumbra_playground_window_core
    PRIVATE penumbra_imgui_backends)
if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(penumbra_playground_window PRIVATE -Wall -Wextra)
    # GCC 12 reports a bogus -Wrestrict inside std::string concatenation (GCC bug 105329).
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
        target_compile_options(penumbra_playground_window PRIVATE -Wno-restrict)
    endif()
    target_compile_options(penumbra_playground_window_core PRIVATE -Wall -Wextra)
endif()
