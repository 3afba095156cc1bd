#include "panel.hpp"

#include "rendering/debug_views.hpp"
#include "scenes/scenes.hpp"

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cstdio>
#include <string>
#include <type_traits>

namespace penumbra::playground {

namespace {

template <class Enum> bool enum_combo(const char* label, Enum& value) {
    bool changed = false;
    if (ImGui::BeginCombo(label, std::string(to_string(value)).c_str())) {
        for (Enum candidate : all_values<Enum>()) {
            if constexpr (std::is_same_v<Enum, Target>)
                if (candidate == Target::vulkan) continue; // SPIR-V: nothing the GL runtime can run
            const bool selected = candidate == value;
            if (ImGui::Selectable(std::string(to_string(candidate)).c_str(), selected)) {
                changed = !selected;
                value = candidate;
            }
        }
        ImGui::EndCombo();
    }
    return changed;
}

// Returns true when the user changed something; `config` then holds the request.
// Side of a power-of-two texture as a combo over 32 … 32·2^(count−1).
bool power_of_two_combo(const char* label, int& side, int count) {
    static const char* sides[] = {"32", "64", "128", "256", "512", "1024", "2048", "4096", "8192"};
    int level = 0;
    for (int r = side; r > 32; r /= 2) ++level;
    if (!ImGui::Combo(label, &level, sides, count)) return false;
    side = 32 << level;
    return true;
}

// The parameters of the shadow-map family (shadowmap, pcf, pcss); validation happens when applied.
bool shadow_map_editor(Config& config) {
    bool changed = power_of_two_combo("shadow map", config.shadow_map.resolution, 9);
    float bias[2] = {float(config.shadow_map.constant_bias), float(config.shadow_map.slope_bias)};
    if (ImGui::DragFloat2("bias: constant, slope", bias, 0.005f, 0.0f, 16.0f, "%.3f")) {
        config.shadow_map.constant_bias = bias[0];
        config.shadow_map.slope_bias = bias[1];
        changed = true;
    }
    float normal_offset = float(config.shadow_map.normal_offset);
    if (config.technique != Technique::erosion &&
        ImGui::DragFloat("normal offset (texels x sin)", &normal_offset, 0.05f, 0.0f, 8.0f, "%.2f")) {
        config.shadow_map.normal_offset = normal_offset;
        changed = true;
    }
    if (config.technique == Technique::pcf || config.technique == Technique::pcss)
        changed |= ImGui::Checkbox("receiver-plane depth bias", &config.shadow_map.receiver_plane_bias);
    if (config.technique == Technique::pcf) {
        changed |= enum_combo("pattern", config.pcf.pattern);
        if (config.pcf.pattern == TapPattern::grid)
            changed |= ImGui::SliderInt("grid N (N x N taps)", &config.pcf.grid_size, 1, 16);
        else
            changed |= ImGui::SliderInt("Poisson taps", &config.pcf.poisson_taps, 1, 64);
        float radius = float(config.pcf.radius);
        if (ImGui::DragFloat("radius (scene units)", &radius, 0.005f, 0.001f, 10.0f, "%.3f")) {
            config.pcf.radius = radius;
            changed = true;
        }
        changed |= ImGui::Checkbox("rotate per pixel", &config.pcf.rotate);
    }
    if (config.technique == Technique::pcss) {
        static const int presets[][2] = {{8, 8}, {16, 16}, {17, 34}, {32, 32}, {32, 64}};
        static const char* names[] = {"8/8 (Bevy)", "16/16 (Filament)", "17/34 (three.js)", "32/32 (Godot ultra)",
                                      "32/64 (PlayCanvas high)"};
        int preset = -1;
        for (int i = 0; i < 5; ++i)
            if (config.pcss.blocker_samples == presets[i][0] && config.pcss.filter_samples == presets[i][1]) preset = i;
        if (ImGui::Combo("engine preset", &preset, names, 5)) {
            config.pcss.blocker_samples = presets[preset][0];
            config.pcss.filter_samples = presets[preset][1];
            changed = true;
        }
        changed |= ImGui::SliderInt("blocker samples", &config.pcss.blocker_samples, 1, 64);
        changed |= ImGui::SliderInt("filter samples", &config.pcss.filter_samples, 1, 128);
        changed |= ImGui::SliderInt("max filter texels", &config.pcss.max_filter_texels, 1,
                                    config.shadow_map.resolution / 2);
        changed |= ImGui::Checkbox("rotate per pixel", &config.pcss.rotate);
    }
    return changed;
}

bool config_editor(const char* id, Config& config) {
    ImGui::PushID(id);
    bool changed = enum_combo("technique", config.technique);
    changed |= ImGui::Checkbox("alpha test (cut-out casters)", &config.alpha_test);
    if (config.technique != Technique::occlusion) {
        if (uses_shadow_map(config)) changed |= shadow_map_editor(config);
        changed |= enum_combo("light", config.light);
        changed |= enum_combo("target", config.target);
        ImGui::PopID();
        return changed;
    }
    int channel_slices = std::min(config.slices, max_channel_slices); // 1 to 32: colour channels
    if (ImGui::SliderInt("slices", &channel_slices, 1, max_channel_slices)) {
        config.slices = channel_slices;
        changed = true;
    }
    for (const int bit_slices : {64, 128}) { // paper §3.7: sliced as bits, then unpacked
        ImGui::SameLine();
        if (ImGui::RadioButton(std::to_string(bit_slices).c_str(), config.slices == bit_slices)) {
            config.slices = bit_slices;
            changed = true;
        }
    }
    int level = 0;
    for (int r = config.resolution; r > 32; r /= 2) ++level;
    static const char* resolutions[] = {"32", "64", "128", "256", "512", "1024", "2048", "4096"};
    if (ImGui::Combo("resolution", &level, resolutions, 8)) {
        config.resolution = 32 << level;
        changed = true;
    }
    changed |= enum_combo("filter", config.filter);
    changed |= enum_combo("fusion", config.fusion);
    changed |= enum_combo("packing", config.packing);
    changed |= enum_combo("light", config.light);
    changed |= enum_combo("target", config.target);
    changed |= ImGui::Checkbox("leak fix (§3.4.1)", &config.leak_fix);
    ImGui::SameLine();
    changed |= ImGui::Checkbox("fade (§3.4.2)", &config.self_shadow_fade);
    changed |= ImGui::Checkbox("tangent clip", &config.tangent_clip);
    changed |= ImGui::Checkbox("clip footprint", &config.clip_footprint);
    float offsets[2] = {float(config.tangent_clip_offset), float(config.fade_ramp)};
    if (ImGui::DragFloat2("clip offset (texels), fade ramp (slice)", offsets, 0.05f, 0.0f, 8.0f, "%.2f")) {
        config.tangent_clip_offset = offsets[0];
        config.fade_ramp = std::max(offsets[1], 0.01f);
        changed = true;
    }
    changed |= enum_combo("slice placement (§5)", config.slice_placement);
    if (config.packing == Packing::atlas && (config.filter == Filter::nbuffer || config.filter == Filter::gaussian))
        changed |= ImGui::SliderInt("level reduction", &config.level_reduction, -1, resolution_levels(config),
                                    config.level_reduction < 0 ? "off" : "above %d");
    if (config.packing == Packing::atlas && config.filter == Filter::nbuffer && config.target == Target::glsl450)
        changed |= enum_combo("prefilter stage", config.prefilter_stage);
    ImGui::PopID();
    return changed;
}

void scene_section(WindowApp& app) {
    if (ImGui::BeginCombo("scene", app.scene_name().c_str())) {
        for (std::string_view name : scene_names())
            if (ImGui::Selectable(std::string(name).c_str(), name == app.scene_name()))
                app.load_scene(std::string(name));
        ImGui::EndCombo();
    }
    static char obj_path[512] = "";
    ImGui::InputText("mesh file (.obj, .gltf, .glb)", obj_path, sizeof obj_path);
    ImGui::SameLine();
    if (ImGui::Button("load")) app.load_scene(obj_path);
}

void light_section(WindowApp& app) {
    Controls& c = app.controls();
    if (app.config().light == Light::rect) {
        glm::vec3 centre(c.rect.center);
        if (ImGui::DragFloat3("light centre", &centre.x, 0.05f)) c.rect.center = glm::dvec3(centre);
        float size[2] = {float(c.rect.width), float(c.rect.height)};
        if (ImGui::DragFloat2("width x height", size, 0.02f, 0.01f, 100.0f)) {
            c.rect.width = std::max(size[0], 0.01f);
            c.rect.height = std::max(size[1], 0.01f);
        }
        ImGui::SliderFloat("yaw", &c.rect_yaw_degrees, -180.0f, 180.0f, "%.0f deg");
        ImGui::SliderFloat("tilt", &c.rect_tilt_degrees, -80.0f, 80.0f, "%.0f deg");
    } else {
        ImGui::SliderFloat("sun azimuth", &c.sun_azimuth_degrees, -180.0f, 180.0f, "%.0f deg");
        ImGui::SliderFloat("sun elevation", &c.sun_elevation_degrees, 5.0f, 90.0f, "%.0f deg");
        ImGui::SliderFloat("angular diameter", &c.sun_diameter_degrees, 0.05f, 20.0f, "%.2f deg");
    }
    ImGui::Checkbox("moving light", &c.animate_light);
    ImGui::SameLine();
    ImGui::Checkbox("moving object", &c.animate_object);
}

void view_section(WindowApp& app) {
    Controls& c = app.controls();
    int view = static_cast<int>(c.view);
    static const char* views[view_count] = {"shaded",
                                            "visibility only",
                                            "ground truth (Embree, oriented)",
                                            "error heatmap",
                                            "slice occlusion texture",
                                            "slice per pixel",
                                            "filter level per pixel",
                                            "any texture of the layout"};
    if (ImGui::Combo("view", &view, views, view_count)) c.view = static_cast<View>(view);
    const Config& config = app.config();
    if (c.view == View::slice_texture) {
        ImGui::SliderInt("slice", &c.view_slice, 0, config.slices - 1);
        ImGui::SliderInt("filter level", &c.view_level, 0, max_level(config));
    } else if (c.view == View::level_map) {
        ImGui::SliderInt("slice (-1: nearest above)", &c.view_slice, -1, config.slices - 1);
    } else if (c.view == View::texture) {
        const std::vector<TextureDesc>& textures = app.layout().textures;
        const char* current = c.view_texture.texture.empty() && !textures.empty() ? textures.front().name.c_str()
                                                                                  : c.view_texture.texture.c_str();
        int mip_levels = 1, layers = 1;
        if (ImGui::BeginCombo("texture", current)) {
            for (const TextureDesc& t : textures)
                if (ImGui::Selectable((t.name + "  (" + std::string(to_string(t.format)) + ", " + std::string(to_string(t.source)) + ")").c_str(),
                                      t.name == current)) {
                    c.view_texture = {.texture = t.name};
                    if (is_depth(t.format)) c.view_texture.max_value = 1.0f;
                }
            ImGui::EndCombo();
        }
        for (const TextureDesc& t : textures)
            if (t.name == current) {
                mip_levels = t.mip_levels;
                layers = t.target == TextureTarget::texture_2d ? 1 : t.depth;
            }
        if (mip_levels > 1) ImGui::SliderInt("level", &c.view_texture.level, 0, mip_levels - 1);
        if (layers > 1) ImGui::SliderInt("layer", &c.view_texture.layer, 0, layers - 1);
        ImGui::SliderInt("channel (r g b a)", &c.view_texture.channel, 0, 3);
        ImGui::DragFloatRange2("black .. white", &c.view_texture.min_value, &c.view_texture.max_value, 0.01f);
    } else if (c.view == View::slice_map) {
        for (int k = 0; k < config.slices; ++k) { // legend, debug_views.hpp colours
            const glm::vec3 color = slice_color(k);
            if (k % 8) ImGui::SameLine();
            ImGui::ColorButton(("slice " + std::to_string(k)).c_str(), ImVec4(color.r, color.g, color.b, 1),
                               ImGuiColorEditFlags_NoTooltip, ImVec2(14, 14));
        }
    }
    if (c.view == View::truth || c.view == View::error) {
        const TruthSnapshot& t = app.truth();
        ImGui::ProgressBar(static_cast<float>(t.progress), ImVec2(-1, 0));
        ImGui::Text("truth (oriented: the light above each surface's tangent plane): %s, %dx%d rays/pixel done, "
                    "%.1f s",
                    to_string(t.state), t.samples_per_axis,
                    t.samples_per_axis, t.seconds);
        for (int side = 0; side < (c.split ? 2 : 1); ++side)
            ImGui::Text("%sMAE %.4f  p95 %.4f  over %zu px", c.split ? (side ? "right: " : "left: ") : "",
                        app.error_numbers(side).mae, app.error_numbers(side).p95,
                        app.error_numbers(side).count);
        if (c.view == View::error)
            ImGui::TextUnformatted("|error| 0 black to 0.25 yellow-white; green: not traced yet, or the pixel sees "
                                   "none of the light");
    }
    ImGui::Checkbox("split screen (right: second configuration)", &c.split);
    if (c.split && ImGui::TreeNode("right configuration")) {
        Config right = app.config(1);
        if (config_editor("right", right)) app.request_config(right, 1);
        ImGui::TreePop();
    }
}

void shader_section(WindowApp& app) {
    ShaderSession& shaders = app.shaders();
    ImGui::TextWrapped("folder: %s (save a file to recompile it)", shaders.folder().directory().c_str());
    for (const ShaderFile& file : shaders.runtime().emission().files()) {
        const auto error = shaders.errors().find(file.file_name);
        if (error != shaders.errors().end())
            ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s  error", file.file_name.c_str());
        else
            ImGui::Text("%s", file.file_name.c_str());
    }
    if (ImGui::Button("reset to generated")) app.reset_to_generated();
    for (const auto& [file, text] : shaders.errors()) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.45f, 0.45f, 1));
        ImGui::TextUnformatted(text.c_str());
        ImGui::PopStyleColor();
    }
}

void timing_section(WindowApp& app) {
    FrameStats& stats = app.stats();
    char overlay[64];
    std::snprintf(overlay, sizeof overlay, "frame %.1f ms (median %.1f)", stats.frame.last(),
                  stats.frame.median());
    const auto& plot = stats.frame.plot();
    ImGui::PlotLines("##frame", plot.data(), static_cast<int>(plot.size()), 0, overlay, 0.0f, FLT_MAX,
                     ImVec2(-1, 60));
    if (ImGui::BeginTable("passes", 3, ImGuiTableFlags_SizingStretchProp)) {
        ImGui::TableSetupColumn("GPU pass");
        ImGui::TableSetupColumn("last ms");
        ImGui::TableSetupColumn("plot");
        ImGui::TableHeadersRow();
        for (const std::string& name : stats.pass_order) {
            const TimeSeries& series = stats.passes.at(name);
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(name.c_str());
            ImGui::TableNextColumn();
            ImGui::Text("%.2f", series.last());
            ImGui::TableNextColumn();
            ImGui::PlotLines(("##" + name).c_str(), series.plot().data(),
                             static_cast<int>(series.plot().size()), 0, nullptr, 0.0f, FLT_MAX,
                             ImVec2(-1, 16));
        }
        ImGui::EndTable();
    }
}

void overwrite_question(WindowApp& app) {
    if (app.overwrite_question() && !ImGui::IsPopupOpen("Overwrite edited shaders?"))
        ImGui::OpenPopup("Overwrite edited shaders?");
    if (ImGui::BeginPopupModal("Overwrite edited shaders?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::Text("The new configuration rewrites every shader file. Edited by hand:");
        for (const std::string& f : app.overwrite_files()) ImGui::BulletText("%s", f.c_str());
        if (ImGui::Button("overwrite and apply")) {
            app.answer_overwrite(true);
            ImGui::CloseCurrentPopup();
        }
        ImGui::SameLine();
        if (ImGui::Button("cancel (keep my edits)")) {
            app.answer_overwrite(false);
            ImGui::CloseCurrentPopup();
        }
        if (!app.overwrite_question()) ImGui::CloseCurrentPopup(); // answered by a script
        ImGui::EndPopup();
    }
}

} // namespace

void draw_panel(WindowApp& app) {
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(380, 0), ImGuiCond_FirstUseEver);
    ImGui::Begin("Penumbra");
    if (ImGui::CollapsingHeader("configuration", ImGuiTreeNodeFlags_DefaultOpen)) {
        Config config = app.config();
        if (config_editor("main", config)) app.request_config(config);
        if (!app.config_message().empty())
            ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", app.config_message().c_str());
    }
    if (ImGui::CollapsingHeader("scene and camera")) {
        scene_section(app);
        ImGui::TextUnformatted("left drag: orbit, right drag or wheel: zoom");
        if (ImGui::Button("reset camera")) app.reset_camera();
    }
    if (ImGui::CollapsingHeader("light and animation", ImGuiTreeNodeFlags_DefaultOpen)) light_section(app);
    if (ImGui::CollapsingHeader("view", ImGuiTreeNodeFlags_DefaultOpen)) view_section(app);
    if (ImGui::CollapsingHeader("timings", ImGuiTreeNodeFlags_DefaultOpen)) timing_section(app);
    if (ImGui::CollapsingHeader("shaders (hot reload)", ImGuiTreeNodeFlags_DefaultOpen)) shader_section(app);
    overwrite_question(app);
    ImGui::End();
}

} // namespace penumbra::playground
