# penumbra_playground_window: the interactive window (GLFW, Dear ImGui, hot reload).
# Included from playground/CMakeLists.txt; defines the library linked into penumbra-playground.
add_library(penumbra_playground_window STATIC ${CMAKE_CURRENT_LIST_DIR}/app.cpp)
target_link_libraries(penumbra_playground_window PUBLIC penumbra_playground_headless)
