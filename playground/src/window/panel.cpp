#include "panel.hpp"

#include "rendering/debug_views.hpp"
#include "scenes/scenes.hpp"

#include <imgui.h>
#include <penumbra/config_fields.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace penumbra::playground {

namespace {

// The highest value a field's widget offers where the table gives no maximum (it depends on another field).
int widget_max(const ConfigField& f, const Config& config) {
    if (std::isfinite(f.max)) return static_cast<int>(f.max);
    if (f.key == "pcss.max_filter_texels") return config.shadow_map.resolution / 2;
    return resolution_levels(config); // level_bound, level_reduction
}

// One field of the table (penumbra/config_fields.hpp) as a widget: a checkbox, a combo of its names
// or of the powers of two it allows, a slider over its range, a drag for a real; its flag and help as
// the tooltip. Validation happens when the configuration is applied.
bool field_widget(const ConfigField& f, Config& config) {
    const std::string label(f.key);
    const double value = f.get(config);
    double next = value;
    switch (f.kind) {
    case FieldKind::boolean: {
        bool on = value != 0.0;
        if (ImGui::Checkbox(label.c_str(), &on)) next = on ? 1.0 : 0.0;
        break;
    }
    case FieldKind::choice:
        if (ImGui::BeginCombo(label.c_str(), std::string(f.names[static_cast<std::size_t>(value)]).c_str())) {
            for (std::size_t i = 0; i < f.names.size(); ++i) {
                if (f.key == "target" && f.names[i] == "vulkan") continue; // SPIR-V: nothing the GL runtime can run
                if (ImGui::Selectable(std::string(f.names[i]).c_str(), i == static_cast<std::size_t>(value)))
                    next = static_cast<double>(i);
            }
            ImGui::EndCombo();
        }
        break;
    case FieldKind::integer: {
        int number = static_cast<int>(value);
        if (f.power_of_two) {
            std::vector<std::string> sides;
            int at = 0;
            for (int side = static_cast<int>(f.min); side <= static_cast<int>(f.max); side *= 2) {
                if (side == number) at = static_cast<int>(sides.size());
                sides.push_back(std::to_string(side));
            }
            std::vector<const char*> items;
            for (const std::string& side : sides) items.push_back(side.c_str());
            if (ImGui::Combo(label.c_str(), &at, items.data(), static_cast<int>(items.size())))
                next = static_cast<double>(static_cast<int>(f.min) << at);
        } else if (ImGui::SliderInt(label.c_str(), &number, static_cast<int>(f.min), widget_max(f, config))) {
            next = number;
        }
        break;
    }
    case FieldKind::real: {
        float number = static_cast<float>(value);
        const float lo = static_cast<float>(f.min_exclusive ? f.min + 0.01 : f.min);
        const float hi = static_cast<float>(f.max);
        if (ImGui::DragFloat(label.c_str(), &number, std::max(0.001f, 0.01f * std::abs(number)), lo, hi, "%.3f"))
            next = std::clamp(number, lo, hi);
        break;
    }
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s: %s", std::string(f.flag).c_str(), std::string(f.help).c_str());
    if (next == value) return false;
    f.set(config, next);
    return true;
}

// Slices: a slider over the colour-channel counts (1 to 32) and buttons for the counts sliced as bits
// (64, 128; paper §3.7).
bool slices_widget(Config& config) {
    bool changed = false;
    int channel_slices = std::min(config.slices, max_channel_slices);
    if (ImGui::SliderInt("slices", &channel_slices, 1, max_channel_slices)) {
        config.slices = channel_slices;
        changed = true;
    }
    for (const int bit_slices : {64, 128}) {
        ImGui::SameLine();
        if (ImGui::RadioButton(std::to_string(bit_slices).c_str(), config.slices == bit_slices)) {
            config.slices = bit_slices;
            changed = true;
        }
    }
    return changed;
}

// PCSS's sample counts as shipped by engines: two fields at once.
bool pcss_presets(Config& config) {
    static const int presets[][2] = {{8, 8}, {16, 16}, {17, 34}, {32, 32}, {32, 64}};
    static const char* names[] = {"8/8 (Bevy)", "16/16 (Filament)", "17/34 (three.js)", "32/32 (Godot ultra)",
                                  "32/64 (PlayCanvas high)"};
    int preset = -1;
    for (int i = 0; i < 5; ++i)
        if (config.pcss.blocker_samples == presets[i][0] && config.pcss.filter_samples == presets[i][1]) preset = i;
    if (!ImGui::Combo("engine preset", &preset, names, 5)) return false;
    config.pcss.blocker_samples = presets[preset][0];
    config.pcss.filter_samples = presets[preset][1];
    return true;
}

// Returns true when the user changed something; `config` then holds the request. Every field the
// selected technique reads, in table order.
bool config_editor(const char* id, Config& config) {
    ImGui::PushID(id);
    bool changed = false;
    const Technique technique = config.technique;
    for (const ConfigField& f : config_fields()) {
        if (!reads_field(f, technique)) continue;
        ImGui::PushID(f.key.data(), f.key.data() + f.key.size());
        if (f.key == "pcss.blocker_samples") changed |= pcss_presets(config);
        changed |= f.key == "slices" ? slices_widget(config) : field_widget(f, config);
        ImGui::PopID();
    }
    ImGui::PopID();
    return changed;
}

void scene_section(WindowApp& app) {
    if (ImGui::BeginCombo("scene", app.scene_name().c_str())) {
        for (const auto& names : {scene_names(), room_scene_names()})
            for (std::string_view name : names)
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
                                            "ground truth (Embree)",
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
        // irradiance first: the light term times the visibility is the shaded image, so its error is the
        // image's
        int reference = static_cast<int>(c.truth_reference);
        static const char* references[truth_reference_count] = {
            "irradiance (the shaded image's reference)", "oriented (the light above the tangent plane)",
            "whole light (orientation aside)"};
        if (ImGui::Combo("reference", &reference, references, truth_reference_count))
            c.truth_reference = static_cast<TruthReference>(reference);
        ImGui::Text("truth (%s): %s, %dx%d rays/pixel done, %.1f s", to_string(c.truth_reference),
                    to_string(t.state), t.samples_per_axis, t.samples_per_axis, t.seconds);
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
