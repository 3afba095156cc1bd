// playground/src/window/panel.hpp — the Dear ImGui panel: configuration, scene, light, camera,
// animation, view, shader files and diagnostics, timings. Everything goes through WindowApp.
#pragma once

#include "window_app.hpp"

namespace penumbra::playground {

void draw_panel(WindowApp& app);

} // namespace penumbra::playground
