// layout.json vocabulary (layout version 3): phases, structured render state, output-sized and
// caller textures, border colours, uniform sources. No glslang, no GL.
#include <penumbra/penumbra.hpp>
#include <penumbra/cost_model.hpp>
#include <penumbra/uniform_values.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>

using namespace penumbra;

namespace {

std::vector<Config> vocabulary_configs() {
    std::vector<Config> configs;
    for (Filter filter : all_values<Filter>())
        for (Packing packing : all_values<Packing>())
            for (Light light : all_values<Light>())
                for (Target target : all_values<Target>()) {
                    Config c{.slices = 5, .resolution = 64, .filter = filter, .packing = packing, .light = light,
                             .target = target};
                    if (is_valid(c)) configs.push_back(c);
                }
    return configs;
}

using penumbra::detail::find_texture;

} // namespace

TEST_CASE("layout v3: version, technique, the screen pass and its result") {
    const std::vector<Config> configs = vocabulary_configs();
    REQUIRE(configs.size() > 40);
    for (const Config& config : configs) {
        CAPTURE(to_string(config.filter));
        CAPTURE(to_string(config.packing));
        CAPTURE(to_string(config.light));
        CAPTURE(to_string(config.target));
        const Layout layout = describe_layout(config);
        CHECK(layout.version == 3);
        CHECK(layout.config.technique == Technique::occlusion);
        const std::string json = to_json(layout);
        CHECK(json.find("\"layout_version\": 3,") != std::string::npos);
        CHECK(json.find("\"technique\": \"occlusion\",") != std::string::npos);
        CHECK(json.find("\"result\": \"penumbra_visibility\",") != std::string::npos);

        // The G-buffer is the caller's, sized like the output; the result is ours, sized like the output.
        const TextureDesc* world = find_texture(layout, "penumbra_worldPositions");
        REQUIRE(world);
        CHECK(world->source == TextureSource::caller);
        CHECK(world->size == TextureSize::output);
        CHECK(world->format == TextureFormat::rgba32f);
        CHECK(world->width == 0);
        CHECK(world->purpose.find("texelFetch") != std::string::npos);
        const TextureDesc* result = find_texture(layout, layout.result);
        REQUIRE(result);
        CHECK(result->source == TextureSource::passes);
        CHECK(result->size == TextureSize::output);
        CHECK(result->format == (config.target == Target::essl300 ? TextureFormat::r8 : TextureFormat::r32f));

        // Exactly one screen pass writes the result; it reads the G-buffer and every storage sampler the
        // example pass reads, at the same bindings as the deferred program declares.
        std::set<Phase> phases;
        const PassDesc* screen = nullptr;
        const PassDesc* example = nullptr;
        for (const PassDesc& pass : layout.passes) {
            phases.insert(pass.phase);
            if (pass.phase == Phase::screen) {
                CHECK(screen == nullptr);
                screen = &pass;
            }
            if (pass.phase == Phase::example) example = &pass;
        }
        CHECK(phases == std::set<Phase>{Phase::shadow, Phase::screen, Phase::example});
        REQUIRE(screen);
        REQUIRE(example);
        CHECK(screen->program == "shading_deferred");
        CHECK(screen->action == PassAction::fullscreen);
        CHECK(screen->viewport_width == 0);
        REQUIRE(screen->outputs.size() == 1);
        CHECK(screen->outputs[0].texture == layout.result);
        CHECK(attachment_kind(layout, screen->outputs[0]) == AttachmentKind::color);
        std::set<std::string> screen_reads, example_reads;
        for (const BindingDesc& b : screen->inputs) screen_reads.insert(b.texture);
        for (const BindingDesc& b : example->inputs) example_reads.insert(b.texture);
        CHECK(screen_reads.count("penumbra_worldPositions") == 1);
        example_reads.insert("penumbra_worldPositions");
        // the tangent clip's normals: a vertex attribute of the example pass, a G-buffer of the screen pass
        if (reads_receiver_normal(config)) example_reads.insert("penumbra_worldNormals");
        CHECK(screen_reads == example_reads);
        CHECK(example->program == "shading_example");
        CHECK(example->state.depth_test);
        CHECK(json.find("\"phase\": \"screen\", \"action\": \"fullscreen\", \"program\": \"shading_deferred\"") !=
              std::string::npos);
    }
}

TEST_CASE("layout: structured state, border colours, attachment kinds, levels") {
    for (const Config& config : vocabulary_configs()) {
        CAPTURE(to_string(config.filter));
        CAPTURE(to_string(config.packing));
        CAPTURE(to_string(config.target));
        const Layout layout = describe_layout(config);
        const std::string json = to_json(layout);
        // slicing: blend MAX with factors ONE, ONE over a target cleared to 0; nothing else
        const RenderState& slicing = layout.passes.front().state;
        CHECK(layout.passes.front().name == "slicing");
        CHECK(slicing.blend);
        CHECK(slicing.blend_equation == BlendEquation::max);
        CHECK(slicing.blend_src == BlendFactor::one);
        CHECK(slicing.blend_dst == BlendFactor::one);
        REQUIRE(slicing.clear_color.has_value());
        CHECK(*slicing.clear_color == std::array<float, 4>{0.0f, 0.0f, 0.0f, 0.0f});
        CHECK_FALSE(slicing.depth_test);
        CHECK(slicing.cull == Cull::none);
        CHECK(json.find("\"state\": {\"blend\": true, \"blend_equation\": \"MAX\", \"blend_src\": \"ONE\", "
                        "\"blend_dst\": \"ONE\", \"depth_test\": false") != std::string::npos);
        CHECK(json.find("\"clear_color\": [0, 0, 0, 0], \"clear_depth\": null") != std::string::npos);
        for (const PassDesc& pass : layout.passes) {
            CAPTURE(pass.name);
            if (pass.action == PassAction::fullscreen) CHECK_FALSE(pass.state.blend);
            for (const AttachmentDesc& out : pass.outputs) CHECK(attachment_kind(layout, out) == AttachmentKind::color);
            // one level is bound only by a mip chain's pass, which renders the next level of that texture (WGSL:
            // WebGPU has no generateMipmap)
            for (const BindingDesc& in : pass.inputs)
                CHECK((in.level == -1 || (detail::binds_samplers_apart(config) && pass.outputs.at(0).texture == in.texture &&
                                          pass.outputs.at(0).level == in.level + 1)));
        }
        // a border colour exactly where the wrap is CLAMP_TO_BORDER, in textures and in samplings (ES 3.0
        // has none)
        int borders = 0;
        for (const TextureDesc& t : layout.textures) {
            CHECK((t.size == TextureSize::fixed) == (t.width > 0));
            borders += t.wrap == Wrap::clamp_to_border;
        }
        auto count = [&](std::string_view text) {
            int n = 0;
            for (std::size_t at = json.find(text); at != std::string::npos; at = json.find(text, at + 1)) ++n;
            return n;
        };
        CHECK(count("\"border_color\": [0, 0, 0, 0]") == count("\"wrap\": \"CLAMP_TO_BORDER\""));
        CHECK(count("\"border_color\"") == count("\"wrap\": \"CLAMP_TO_BORDER\""));
        CHECK((borders == 0) == (config.target == Target::essl300 || config.target == Target::wgsl)); // neither has borders
    }
}

TEST_CASE("uniform_values: one reader per registry row, for each frame its input names") {
    CHECK(penumbra::detail::readers_match_registry());
}

TEST_CASE("layout v2: every plain uniform says where its value comes from, and the table has it") {
    for (const Config& config : vocabulary_configs()) {
        CAPTURE(to_string(config.filter));
        CAPTURE(to_string(config.packing));
        CAPTURE(to_string(config.light));
        const Layout layout = describe_layout(config);
        for (const ProgramDesc& program : layout.programs) {
            CAPTURE(program.name);
            for (const ParamDesc& p : program.parameters) {
                CAPTURE(p.name);
                if (const UniformDef* def = find_uniform(p.name)) { // declared as its registry row says
                    CHECK(p.type == to_string(def->type));
                    CHECK(p.source == def->source);
                    CHECK(p.compute == def->compute(config.light));
                }
                if (p.binding >= 0) {
                    CHECK(!p.source);
                    continue;
                }
                CHECK((p.source == UniformSource::light || p.source == UniformSource::pass || p.source == UniformSource::camera));
                CHECK(p.compute.size() > 10); // layout.json says how to compute every plain uniform
                if (p.source != UniformSource::pass) CHECK(has_uniform_rule(p.name));
                if (p.source != UniformSource::pass) continue;
                // every pass running this program sets it
                for (const PassDesc& pass : layout.passes) {
                    if (pass.program != program.name) continue;
                    bool set = false;
                    for (const auto& [name, value] : pass.int_uniforms) set = set || name == p.name;
                    CHECK(set);
                }
            }
        }
    }
    // every uniform with a value is a registry row that says how to compute it, for both lights
    for (const UniformRule& rule : uniform_rules()) {
        CAPTURE(rule.name);
        const UniformDef* def = find_uniform(rule.name);
        REQUIRE(def != nullptr);
        CHECK(!def->compute(Light::rect).empty());
        CHECK(!def->compute(Light::sun).empty());
    }
    CHECK(find_uniform("penumbra_windowHalfSize")->compute(Light::sun).find("1.001") != std::string_view::npos);
    // the table computes from the frame: rect origin at the light centre, sun direction towards the sun
    RectLight light;
    light.center = {1.0, 5.0, 2.0};
    const UniformInputs rect{slice_frame(light, {-1, 0, -1}, {1, 1, 1}, 4), Light::rect, std::nullopt};
    const auto to_light = std::get<glm::vec4>(*uniform_value("penumbra_toLight", rect));
    CHECK(to_light.x == doctest::Approx(1.0));
    CHECK(to_light.y == doctest::Approx(5.0));
    CHECK(to_light.w == 1.0f);
    CHECK(std::get<glm::vec2>(*uniform_value("penumbra_sliceDepths", rect)) == rect.frame->slice_depths);
    CHECK(uniform_value("penumbra_sliceDepths", rect).error.empty());
}

TEST_CASE("uniform values: a missing input is an error naming what to set, never a value of zeros") {
    RectLight light;
    light.center = {1.0, 5.0, 2.0};
    const UniformInputs frame_only{.frame = slice_frame(light, {-1, 0, -1}, {1, 1, 1}, 4)};
    const UniformInputs shadow_only{.shadow = shadow_frame(light, {-1, 0, -1}, {1, 1, 1})};
    const UniformInputs nothing{};
    struct Row {
        std::string_view uniform;
        const UniformInputs* inputs;
        std::string_view error; // "" when there is a value
    };
    const Row rows[] = {
        {"penumbra_shadowDepthRange", &frame_only,
         "penumbra_shadowDepthRange: UniformInputs::shadow is not set; set it to penumbra::shadow_frame(light, "
         "bounds_min, bounds_max)"},
        {"penumbra_shadowClipFromWorld", &frame_only, "UniformInputs::shadow is not set"},
        {"penumbra_lightSizeUV", &frame_only, "UniformInputs::shadow is not set"},
        {"penumbra_sliceDepths", &shadow_only,
         "penumbra_sliceDepths: UniformInputs::frame is not set; set it to penumbra::slice_frame(light, bounds_min, "
         "bounds_max, slices)"},
        {"penumbra_copDistance", &shadow_only, "UniformInputs::frame is not set"},
        {"penumbra_lightFromWorld", &nothing, "neither UniformInputs::frame nor UniformInputs::shadow is set"},
        {"penumbra_toLight", &nothing, "neither UniformInputs::frame nor UniformInputs::shadow is set"},
        {"penumbra_clipFromWorld", &frame_only, "UniformInputs::clip_from_world is not set"},
        {"penumbra_timeWindow", &frame_only, "UniformInputs::time_window is not set"},
        {"penumbra_noSuchUniform", &frame_only, "penumbra_noSuchUniform: no rule computes this uniform"},
        // the light frame and size are the same in both frames: either one will do
        {"penumbra_lightFromWorld", &shadow_only, ""},
        {"penumbra_toLight", &shadow_only, ""},
        {"penumbra_lightSize", &frame_only, ""},
        {"penumbra_shadowTanHalfFov", &shadow_only, ""},
    };
    for (const Row& row : rows) {
        CAPTURE(row.uniform);
        const UniformResult result = uniform_value(row.uniform, *row.inputs);
        CHECK(result.value.has_value() == row.error.empty());
        if (!row.error.empty()) CHECK(result.error.find(row.error) != std::string::npos);
        else CHECK(result.error.empty());
    }
    // the light's centre from the shadow frame is the one from the slice frame
    const UniformInputs both{.frame = frame_only.frame, .shadow = shadow_only.shadow};
    CHECK(std::get<glm::vec4>(*uniform_value("penumbra_toLight", shadow_only)).y == doctest::Approx(5.0));
    CHECK(std::get<glm::vec4>(*uniform_value("penumbra_toLight", both)).y == doctest::Approx(5.0));
}

TEST_CASE("layout v2: more than 32 slices are sliced as OR-ed bits, then unpacked into the occlusion textures") {
    for (int slices : {64, 128})
        for (Filter filter : {Filter::mipmap, Filter::nbuffer, Filter::sat})
            for (Packing packing : {Packing::atlas, Packing::array})
                for (Target target : {Target::glsl330, Target::glsl450, Target::vulkan}) {
                    const Config config{.slices = slices, .resolution = 32, .filter = filter,
                                        .fusion = Fusion::chained, .packing = packing, .leak_fix = true, .tangent_clip = true,
                                        .target = target};
                    CAPTURE(slices);
                    CAPTURE(to_string(filter));
                    CAPTURE(to_string(packing));
                    CAPTURE(to_string(target));
                    if (!is_valid(config)) { // 32 tiles of 33 texels: wider than glsl330's 1024
                        CHECK((slices == 128 && filter == Filter::sat && packing == Packing::atlas &&
                               target == Target::glsl330));
                        continue;
                    }
                    const Layout layout = describe_layout(config);
                    // slicing: one RGBA32UI target, cleared to 0, fragments OR-ed, no blending
                    const PassDesc& slicing = layout.passes.front();
                    CHECK(slicing.name == "slicing");
                    REQUIRE(slicing.outputs.size() == 1);
                    const TextureDesc* bits = find_texture(layout, slicing.outputs[0].texture);
                    REQUIRE(bits);
                    CHECK(bits->format == TextureFormat::rgba32ui);
                    CHECK(bits->min_filter == TextureFilter::nearest);
                    CHECK(slicing.state.logic_op == LogicOp::bitwise_or);
                    CHECK_FALSE(slicing.state.blend);
                    CHECK(slicing.state.clear_color == std::array<float, 4>{0.0f, 0.0f, 0.0f, 0.0f});
                    CHECK(to_json(layout).find("\"logic_op\": \"OR\"") != std::string::npos);
                    // the unpack draws write every occlusion texture's slicing attachment once, in order, at
                    // most the target's colour attachments per draw, each from its first slice
                    const int T = texture_count(config), per_draw = target == Target::vulkan ? 4 : 8;
                    std::vector<AttachmentDesc> written;
                    int draws = 0;
                    for (const PassDesc& pass : layout.passes) {
                        if (pass.program != "unpack_slices") continue;
                        CHECK(pass.state.logic_op == LogicOp::none);
                        CHECK(static_cast<int>(pass.outputs.size()) == per_draw);
                        REQUIRE(pass.int_uniforms.size() == 1);
                        CHECK(pass.int_uniforms[0] == std::pair<std::string, int>{"penumbra_firstSlice", 4 * per_draw * draws});
                        REQUIRE(pass.inputs.size() == 1);
                        CHECK(pass.inputs[0].texture == bits->name);
                        written.insert(written.end(), pass.outputs.begin(), pass.outputs.end());
                        ++draws;
                    }
                    CHECK(draws == T / per_draw);
                    REQUIRE(static_cast<int>(written.size()) == T);
                    for (int t = 0; t < T; ++t) {
                        CHECK(written[t].layer == t);
                        CHECK(written[t].level == 0);
                    }
                    CHECK(layout.passes[static_cast<std::size_t>(draws + 1)].program != "unpack_slices");
                }
    // 32 slices and fewer keep the colour channels and MAX blending
    const Layout channels = describe_layout(Config{.slices = 32, .resolution = 32});
    CHECK(channels.passes.front().state.logic_op == LogicOp::none);
    CHECK(channels.passes.front().outputs.size() == 8);
}

// Adaptive slice placement (paper §5): before slicing, four depth-bin draws (16 bins each, four
// layers of penumbra_depthBins), its mip chain, then the boundary pass into penumbra_sliceBoundaries,
// which the slicing pass and both shading passes bind. Uniform placement has none of it.
TEST_CASE("layout: adaptive slice placement runs the depth bins and the boundary pass before slicing") {
    for (Target target : all_values<Target>()) {
        CAPTURE(to_string(target));
        const Config config{.slices = 5, .resolution = 64, .filter = Filter::nbuffer, .fusion = Fusion::chained,
                            .packing = Packing::atlas, .tangent_clip = true,
                            .slice_placement = SlicePlacement::adaptive, .target = target};
        const Layout layout = describe_layout(config);
        const TextureDesc* bins = find_texture(layout, "penumbra_depthBins");
        const TextureDesc* boundaries = find_texture(layout, "penumbra_sliceBoundaries");
        REQUIRE(bins);
        REQUIRE(boundaries);
        CHECK(bins->target == TextureTarget::texture_2d_array);
        CHECK(bins->depth == depth_bins / 4);
        CHECK(bins->mip_levels == depth_bins_read_level + 1);
        CHECK(boundaries->format == TextureFormat::r32ui);
        CHECK(boundaries->width == config.slices + 1);
        CHECK(boundaries->height == 1);
        // the bins' mip chain: generateMipmap, or on WGSL a pass a level and layer (listed once here)
        const bool wgsl = target == Target::wgsl || target == Target::hlsl; // HLSL: WGSL's passes
        std::vector<std::string> order;
        int chain = 0;
        for (const PassDesc& pass : layout.passes) {
            if (pass.phase != Phase::shadow || order.size() >= 7) continue;
            if (pass.name == "depth_bins_level" && ++chain > 1) continue;
            order.push_back(pass.name);
            if (pass.name == "depth_bins") {
                CHECK(pass.outputs.size() == 4);
                CHECK(pass.int_uniforms.at(0).first == "penumbra_firstBin");
                CHECK(pass.int_uniforms.at(0).second == (order.size() - 1) * depth_bins_per_draw);
                CHECK(pass.state.blend_equation == BlendEquation::max);
            }
        }
        CHECK(order == std::vector<std::string>{"depth_bins", "depth_bins", "depth_bins", "depth_bins",
                                                wgsl ? "depth_bins_level" : "depth_bins_mipmaps", "slice_boundaries", "slicing"});
        CHECK(chain == (wgsl ? depth_bins_read_level * depth_bins / 4 : 0));
        for (const PassDesc& pass : layout.passes) {
            if (pass.name != "slicing" && pass.name != "shading" && pass.name != "shading_example") continue;
            bool reads = false;
            for (const BindingDesc& in : pass.inputs) reads = reads || in.texture == "penumbra_sliceBoundaries";
            CHECK_MESSAGE(reads, pass.name, " does not bind penumbra_sliceBoundaries");
        }
        CHECK(to_json(layout).find("\"slice_placement\": \"adaptive\"") != std::string::npos);
    }
    const Layout uniform = describe_layout(Config{.slices = 5, .resolution = 64, .tangent_clip = false,
                                                  .slice_placement = SlicePlacement::uniform});
    CHECK(find_texture(uniform, "penumbra_sliceBoundaries") == nullptr);
    CHECK(find_texture(uniform, "penumbra_depthBins") == nullptr);
}

// Only the levels the kernels reach (penumbra/level_bound.hpp): level_bound caps what is built,
// allocated and read; the summed-area table keeps every doubling step.
TEST_CASE("layout: level_bound builds, allocates and reads only levels 0 to the bound") {
    Config all{.slices = 16, .resolution = 512};
    all.level_reduction = -1; // every level at full resolution (reduced levels: the next test case)
    Config bounded = all;
    bounded.level_bound = 5;
    const Layout full = describe_layout(all), cut = describe_layout(bounded);
    CHECK(full.max_level == 9);
    CHECK(cut.max_level == 5);
    CHECK(to_json(cut).find("\"max_kernel_texels\": 32") != std::string::npos);
    CHECK(to_json(cut).find("\"level_bound\": 5") != std::string::npos);
    CHECK(find_texture(cut, "penumbra_level5") != nullptr);
    CHECK(find_texture(cut, "penumbra_level6") == nullptr);
    auto count = [](const Layout& l, std::string_view pass) {
        int n = 0;
        for (const PassDesc& p : l.passes) n += p.name == pass;
        return n;
    };
    // level 1 comes out of the atlas packing pass (a second colour output), levels 2 to L from one pass each
    CHECK(count(full, "nbuffer_level") == 8);
    CHECK(count(cut, "nbuffer_level") == 4);
    // 16 slices at 512²: ten RGBA8 levels of 2048 × 512 (40 MiB) against six (24 MiB), plus the slices
    CHECK(texture_bytes(full) - texture_bytes(cut) == 4LL * 2048 * 512 * 4);
    Config half = bounded;
    half.level_format = LevelFormat::rgba16f;
    CHECK(texture_bytes(describe_layout(half)) - texture_bytes(cut) == 6LL * 2048 * 512 * 4);
    CHECK(find_texture(describe_layout(half), "penumbra_level3")->format == TextureFormat::rgba16f);
    CHECK(find_texture(cut, "penumbra_level3")->format == TextureFormat::rgba8);
    const std::string shading = std::string(emit(bounded).value->snippet.text);
    CHECK(shading.find("penumbra_level5") != std::string::npos);
    CHECK(shading.find("penumbra_level6") == std::string::npos);
    CHECK(shading.find(", 0.0, 5.0)") != std::string::npos); // the kernel's level clamped to the bound

    Config sat = all;
    sat.filter = Filter::sat;
    Config sat_bounded = sat;
    sat_bounded.level_bound = 2;
    CHECK(count(describe_layout(sat), "sat_pass") == count(describe_layout(sat_bounded), "sat_pass"));

    Config bad = all;
    bad.level_bound = 10;
    REQUIRE(!is_valid(bad));
    CHECK(validate(bad).front().field == "level_bound");
    bad.level_bound = -2;
    CHECK(!is_valid(bad));
}

// Reduced levels (config.level_reduction): the atlas's levels above it halve per level, their
// passes render at that size and read the previous level at the texels their own stand for.
TEST_CASE("layout: levels above level_reduction at half the resolution of the one below") {
    Config config{.slices = 16, .resolution = 512, .level_bound = 6};
    REQUIRE(config.level_reduction == 2); // the default
    const Layout layout = describe_layout(config);
    const int sides[] = {512, 512, 512, 256, 128, 64, 32};
    for (int l = 0; l <= 6; ++l) {
        const TextureDesc* t = find_texture(layout, "penumbra_level" + std::to_string(l));
        REQUIRE(t != nullptr);
        CHECK(t->width == 4 * sides[l]);
        CHECK(t->height == sides[l]);
    }
    std::vector<const PassDesc*> levels;
    for (const PassDesc& p : layout.passes)
        if (p.name == "nbuffer_level") levels.push_back(&p);
    REQUIRE(levels.size() == 5); // levels 2 to 6: the atlas packing pass writes levels 0 and 1
    const PassDesc* pack = nullptr;
    for (const PassDesc& p : layout.passes)
        if (p.name == "pack_atlas") pack = &p;
    REQUIRE(pack != nullptr);
    REQUIRE(pack->outputs.size() == 2);
    CHECK(pack->outputs[0].texture == "penumbra_level0");
    CHECK(pack->outputs[1].texture == "penumbra_level1");
    CHECK(pack->viewport_width == 2048);
    CHECK(pack->inputs.front().texture == "penumbra_slices");
    // level_reduction 0: level 1 is at half the size, so it gets its own pass (one size per pass)
    Config halved = config;
    halved.level_reduction = 0;
    for (const PassDesc& p : describe_layout(halved).passes)
        if (p.name == "pack_atlas") CHECK(p.outputs.size() == 1);
    auto ints = [](const PassDesc& p) {
        std::map<std::string, int> m(p.int_uniforms.begin(), p.int_uniforms.end());
        return m;
    };
    // level 2 from level 1: full resolution, offsets of 2 texels
    CHECK(ints(*levels[0]) == std::map<std::string, int>{{"penumbra_step", 2}, {"penumbra_sourceTile", 512}, {"penumbra_scale", 1}});
    CHECK(levels[0]->viewport_width == 2048);
    // level 3 from level 2 (full): half the size, offsets of 4 level-0 texels = 4 of level 2
    CHECK(ints(*levels[1]) == std::map<std::string, int>{{"penumbra_step", 4}, {"penumbra_sourceTile", 512}, {"penumbra_scale", 2}});
    CHECK(levels[1]->viewport_width == 1024);
    CHECK(levels[1]->viewport_height == 256);
    // level 5 from level 4 (spacing 4): 16 level-0 texels = 4 of level 4
    CHECK(ints(*levels[3]) == std::map<std::string, int>{{"penumbra_step", 4}, {"penumbra_sourceTile", 128}, {"penumbra_scale", 2}});
    CHECK(to_json(layout).find("\"level_reduction\": 2") != std::string::npos);
    // slices (4 MiB) + levels 0 to 2 (4 MiB each) + levels 3 to 6 (a quarter less each time)
    const long long full_level = 2048LL * 512 * 4;
    CHECK(texture_bytes(layout) == full_level * 4 + full_level / 4 + full_level / 16 + full_level / 64 + full_level / 256);
    Config full = config;
    full.level_reduction = -1;
    CHECK(texture_bytes(describe_layout(full)) == full_level * 8);
    // the shading pass reads level 3 at c - (2^2 - 2/2) / 512 = c - 3/512, level 2 at c - 1.5/512
    const std::string shading = std::string(emit(config).value->snippet.text);
    CHECK(shading.find("kernel.y - 0.005859375") != std::string::npos);
    CHECK(shading.find("kernel.y - 0.0029296875") != std::string::npos);
    std::string level_pass;
    const Result<Emission> emission = emit(config);
    for (const Program& program : emission.value->programs)
        if (program.name == "nbuffer_level") level_pass = std::string(program.stages.back().text);
    CHECK(level_pass.find("penumbra_sourceTile") != std::string::npos);
    // the array and the volume keep every level at R² (one size per texture)
    Config array = config;
    array.packing = Packing::array;
    CHECK(find_texture(describe_layout(array), "penumbra_levels")->width == 512);
    Config bad = config;
    bad.level_reduction = 10;
    REQUIRE(!is_valid(bad));
    CHECK(validate(bad).front().field == "level_reduction");
    bad.level_reduction = -2;
    CHECK(!is_valid(bad));
}

TEST_CASE("kernel_level_bound: the widest kernel of a receiver on the bounds' bottom through the top plane") {
    const RectLight light{.center = {0, 5, 0}, .u_axis = {1, 0, 0}, .v_axis = {0, 0, 1}, .width = 1, .height = 1};
    const Config config{.slices = 16, .resolution = 512, .fusion = Fusion::chained};
    const SliceFrame small = slice_frame(light, {-4, 0, -4}, {4, 1, 4}, 16);
    const int bound = kernel_level_bound(small, config);
    // σ = d (z_S − ζ_0) / (z_S (d + ζ_0)) by hand
    const double d = small.cop_distance, z0 = small.slice_depths.x, dz = small.slice_depths.y;
    const double zS = z0 + 16 * dz, zeta = z0 + dz;
    CHECK(bound == static_cast<int>(std::ceil(std::log2(d * (zS - zeta) / (zS * (d + zeta)) * 512))));
    RectLight large = light;
    large.width = large.height = 8;
    CHECK(kernel_level_bound(slice_frame(large, {-4, 0, -4}, {4, 1, 4}, 16), config) > bound);
    Config sat = config;
    sat.filter = Filter::sat;
    CHECK(kernel_level_bound(small, sat) == -1);
    // extent fusion also reads a window twice the kernel's side: one level more
    Config extent = config;
    extent.fusion = Fusion::extent;
    CHECK(kernel_level_bound(small, extent) == bound + 1);
}

TEST_CASE("cost_model: fragments, fetches and bytes per pass, from the layout") {
    Config config{.slices = 16, .resolution = 512};
    config.level_bound = 5;
    config.level_reduction = -1; // every level at full resolution
    const Layout layout = describe_layout(config);
    const CostModel cost = cost_model(layout, 256, 256);
    int levels = 0;
    for (const PassCost& p : cost.passes) {
        if (p.name != "nbuffer_level") continue;
        ++levels;
        CHECK(p.fragments == 2048LL * 512);
        CHECK(p.texel_fetches == 4LL * 2048 * 512);
        CHECK(p.bytes_written == 4LL * 2048 * 512); // RGBA8
        CHECK(p.bytes_read == 4LL * 2048 * 512);    // the previous level, each texel once
    }
    CHECK(levels == 4);
    CHECK(cost.shadow.passes == 1 + 1 + 4); // slicing, pack_atlas (levels 0 and 1), levels 2 to 5
    // the atlas packing pass: level 1's four taps per texel from the slices (4 MiB, each texel once),
    // levels 0 and 1 written
    const PassCost* pack = nullptr;
    for (const PassCost& p : cost.passes)
        if (p.name == "pack_atlas") pack = &p;
    REQUIRE(pack != nullptr);
    CHECK(pack->texel_fetches == 4LL * 2048 * 512);
    CHECK(pack->bytes_read == 4LL * 2048 * 512);
    CHECK(pack->bytes_written == 2 * 4LL * 2048 * 512);
    CHECK(cost.screen.passes == 1);
    CHECK(cost.screen.fragments == 256LL * 256);
    // G-buffer (positions, normals) + 2 bilinear per slice, + 1 for extent fusion's doubled window
    CHECK(cost.screen.texel_fetches == 256LL * 256 * (2 + 16 * (config.fusion == Fusion::extent ? 12 : 8)));
    // the same configuration in half floats moves twice the level bytes
    Config half = config;
    half.level_format = LevelFormat::rgba16f;
    const CostModel wider = cost_model(describe_layout(half), 256, 256);
    CHECK(wider.shadow.bytes() > cost.shadow.bytes());
    CHECK(wider.shadow.texel_fetches == cost.shadow.texel_fetches);

    // reduced levels (the default level_reduction 2): a pass that halves the resolution reads every
    // second texel of the previous level per axis, a quarter of it
    Config reduced{.slices = 16, .resolution = 512, .level_bound = 5};
    const CostModel r = cost_model(describe_layout(reduced), 256, 256);
    std::vector<const PassCost*> built;
    for (const PassCost& p : r.passes)
        if (p.name == "nbuffer_level") built.push_back(&p);
    REQUIRE(built.size() == 4);                     // levels 2 to 5
    CHECK(built[0]->bytes_read == 4LL * 2048 * 512); // level 2 from level 1, full resolution
    CHECK(built[1]->fragments == 1024LL * 256);      // level 3, half the resolution
    CHECK(built[1]->texel_fetches == 4LL * 1024 * 256);
    CHECK(built[1]->bytes_read == 4LL * 2048 * 512 / 4); // a quarter of level 2's texels
    CHECK(built[1]->bytes_written == 4LL * 1024 * 256);
    CHECK(built[2]->bytes_read == 4LL * 1024 * 256 / 4); // a quarter of level 3's
}

namespace {

// Every technique, light and target with a small valid configuration (plus 64 slices and adaptive
// placement for the occlusion textures): the conventions must hold for each.
std::vector<Config> convention_configs() {
    std::vector<Config> configs = vocabulary_configs();
    for (Technique technique : all_values<Technique>())
        for (Light light : all_values<Light>())
            for (Target target : all_values<Target>()) {
                Config c{.technique = technique, .slices = 5, .resolution = 64, .light = light, .target = target};
                c.shadow_map.resolution = 64;
                if (is_valid(c)) configs.push_back(c);
            }
    for (Target target : all_values<Target>()) {
        Config bits{.slices = 64, .resolution = 64, .target = target};
        Config adaptive{.slices = 8, .resolution = 64, .slice_placement = SlicePlacement::adaptive, .target = target};
        for (const Config& c : {bits, adaptive})
            if (is_valid(c)) configs.push_back(c);
        // cut-out casters: penumbra_uv on the caster programs, the draw's material parameters
        for (Technique technique : all_values<Technique>()) {
            Config cut{.technique = technique, .slices = 5, .resolution = 64, .target = target, .alpha_test = true};
            cut.shadow_map.resolution = 64;
            configs.push_back(cut);
        }
        Config adaptive_cut = adaptive;
        adaptive_cut.alpha_test = true;
        configs.push_back(adaptive_cut);
    }
    return configs;
}

} // namespace

TEST_CASE("layout v3: vertex inputs as data, and the vertex stages declare exactly them") {
    for (const Config& config : convention_configs()) {
        CAPTURE(to_string(config.technique));
        CAPTURE(to_string(config.target));
        const Emission e = *emit(config).value;
        for (const ProgramDesc& program : e.layout.programs) {
            CAPTURE(program.name);
            std::string vertex_text;
            for (const Program& p : e.programs)
                if (p.name == program.name)
                    for (const ShaderFile& stage : p.stages)
                        if (stage.stage == Stage::vertex) vertex_text = stage.text;
            REQUIRE_FALSE(vertex_text.empty());
            if (config.target == Target::wgsl) { // the entry point's @location parameters
                const std::size_t entry = vertex_text.find("\nfn main(");
                REQUIRE(entry != std::string::npos);
                const std::string signature = vertex_text.substr(entry, vertex_text.find('\n', entry + 1) - entry);
                int declared = 0;
                for (std::size_t at = signature.find("@location("); at != std::string::npos; at = signature.find("@location(", at + 1))
                    ++declared;
                CHECK(declared == static_cast<int>(program.vertex_inputs.size()));
                for (const VertexInputDesc& in : program.vertex_inputs)
                    CHECK(signature.find("@location(" + std::to_string(in.location) + ") " + in.name + "In: " +
                                         std::string(detail::wgsl_type_name(in.type))) != std::string::npos);
                continue;
            }
            if (config.target == Target::hlsl) { // the entry point's parameters with their locations
                const std::size_t entry = vertex_text.find(" main(");
                REQUIRE(entry != std::string::npos);
                const std::string signature = vertex_text.substr(entry, vertex_text.find('\n', entry + 1) - entry);
                int declared = 0;
                for (std::size_t at = signature.find("[[vk::location("); at != std::string::npos;
                     at = signature.find("[[vk::location(", at + 1))
                    ++declared;
                CHECK(declared == static_cast<int>(program.vertex_inputs.size()));
                for (const VertexInputDesc& in : program.vertex_inputs)
                    CHECK(signature.find("[[vk::location(" + std::to_string(in.location) + ")]] " +
                                         std::string(detail::hlsl_type_name(in.type)) + " " + in.name + "In : TEXCOORD" +
                                         std::to_string(in.location)) != std::string::npos);
                continue;
            }
            int declared = 0;
            for (std::size_t at = vertex_text.find(") in "); at != std::string::npos; at = vertex_text.find(") in ", at + 1))
                ++declared;
            CHECK(declared == static_cast<int>(program.vertex_inputs.size()));
            for (const VertexInputDesc& in : program.vertex_inputs)
                CHECK(vertex_text.find("layout(location = " + std::to_string(in.location) + ") in " + in.type + " " +
                                       in.name + ";") != std::string::npos);
        }
        // every program a draw_scene pass runs reads the position; full-screen ones read nothing
        for (const PassDesc& pass : e.layout.passes) {
            const ProgramDesc* program = nullptr;
            for (const ProgramDesc& p : e.layout.programs)
                if (p.name == pass.program) program = &p;
            if (!program) continue;
            CAPTURE(pass.name);
            if (pass.action == PassAction::fullscreen) CHECK(program->vertex_inputs.empty());
            if (pass.action == PassAction::draw_scene) {
                REQUIRE_FALSE(program->vertex_inputs.empty());
                CHECK(program->vertex_inputs.front().name == "penumbra_position");
            }
        }
    }
}

TEST_CASE("layout: every program file states its stage, the emitted file's own") {
    std::vector<Config> configs = convention_configs();
    configs.push_back(Config{.filter = Filter::nbuffer, .packing = Packing::atlas, .target = Target::glsl450,
                             .prefilter_stage = PrefilterStage::compute});
    for (const Config& config : configs) {
        CAPTURE(to_string(config.technique));
        CAPTURE(to_string(config.target));
        const Emission e = *emit(config).value;
        REQUIRE(e.layout.programs.size() == e.programs.size());
        for (std::size_t i = 0; i < e.programs.size(); ++i) {
            const ProgramDesc& desc = e.layout.programs[i];
            const Program& program = e.programs[i];
            CAPTURE(desc.name);
            REQUIRE(desc.stages.size() == desc.files.size());
            REQUIRE(program.stages.size() == desc.files.size());
            for (std::size_t f = 0; f < desc.files.size(); ++f) {
                CHECK(desc.files[f] == program.stages[f].file_name);
                CHECK(desc.stages[f] == program.stages[f].stage);
                // WGSL: the GLSL name and .wgsl (penumbra_deferred.frag.wgsl)
                std::string file = desc.files[f];
                if (config.target == Target::wgsl && file.ends_with(".wgsl")) file.resize(file.size() - 5);
                if (config.target == Target::hlsl && file.ends_with(".hlsl")) file.resize(file.size() - 5);
                CHECK(std::string_view(file).substr(file.rfind('.') + 1) == stage_extension(desc.stages[f]));
            }
        }
    }
    // in layout.json, next to the files
    const Layout compute = describe_layout(configs.back());
    CHECK(to_json(compute).find("\"files\": [\"penumbra_nbuffer_levels.comp\"], \"stages\": [\"compute\"]") !=
          std::string::npos);
    CHECK(to_json(compute).find("\"files\": [\"penumbra_slicing.vert\", \"penumbra_slicing.frag\"], \"stages\": "
                                "[\"vertex\", \"fragment\"]") != std::string::npos);
}

TEST_CASE("layout v3: every binding states its sampling; only shadow samplers compare") {
    for (const Config& config : convention_configs()) {
        CAPTURE(to_string(config.technique));
        CAPTURE(to_string(config.target));
        const Layout layout = describe_layout(config);
        std::map<std::string, std::string> sampler_types; // program/sampler → GLSL type
        for (const ProgramDesc& program : layout.programs)
            for (const ParamDesc& p : program.parameters) {
                if (p.binding < 0) continue;
                CAPTURE(p.name);
                sampler_types[program.name + "/" + p.name] = p.type;
                if (p.source == UniformSource::draw) { // alpha_test: the caller's texture with the caller's sampler, per draw
                    CHECK(config.alpha_test);
                    CHECK(p.name == "penumbra_alphaTexture");
                    CHECK(p.texture.empty());
                    continue;
                }
                REQUIRE(p.sampling);
                CHECK((p.sampling->compare == CompareFunc::lequal) == p.type.ends_with("Shadow"));
                CHECK(p.set == (config.target == Target::vulkan || detail::binds_samplers_apart(config) ? 0 : -1));
            }
        for (const PassDesc& pass : layout.passes)
            for (const BindingDesc& in : pass.inputs) {
                CAPTURE(pass.name);
                CAPTURE(in.sampler);
                const TextureDesc* t = find_texture(layout, in.texture);
                REQUIRE(t);
                CHECK(in.sampling.wrap == t->wrap);
                if (in.sampling.compare) {
                    CHECK(is_depth(t->format));
                    CHECK(sampler_types[pass.program + "/" + in.sampler].ends_with("Shadow"));
                }
            }
        // initial contents: the passes' textures start at zero, the others are the engine's
        for (const TextureDesc& t : layout.textures)
            CHECK(to_string(initial_contents(t)) ==
                  (t.source == TextureSource::passes ? std::string_view("zero") : to_string(t.source)));
    }
}

TEST_CASE("layout v3: copy and generate_mipmap passes say what they do; the slice map names every slice") {
    int copies = 0, mipmaps = 0;
    for (const Config& config : convention_configs()) {
        CAPTURE(to_string(config.technique));
        CAPTURE(to_string(config.filter));
        CAPTURE(to_string(config.packing));
        const Layout layout = describe_layout(config);
        for (const PassDesc& pass : layout.passes) {
            CAPTURE(pass.name);
            if (pass.action == PassAction::copy) { // a region inside both textures
                ++copies;
                REQUIRE(pass.inputs.size() == 1);
                REQUIRE(pass.outputs.size() == 1);
                const CopyDesc copy = copy_region(pass);
                const TextureDesc* from = find_texture(layout, pass.inputs[0].texture);
                const TextureDesc* to = find_texture(layout, pass.outputs[0].texture);
                REQUIRE(from);
                REQUIRE(to);
                CHECK(copy.width > 0);
                CHECK(copy.width <= std::min(from->width >> copy.source_level, to->width >> copy.target_level));
                CHECK(copy.height <= std::min(from->height >> copy.source_level, to->height >> copy.target_level));
                CHECK(copy.target_layer < to->depth);
                CHECK(from->format == to->format);
            }
            if (pass.action == PassAction::generate_mipmap) {
                ++mipmaps;
                REQUIRE(pass.outputs.size() == 1);
                const TextureDesc* t = find_texture(layout, pass.outputs[0].texture);
                REQUIRE(t);
                CHECK(t->mip_levels > 1);
                CHECK(mipmap_range(layout, pass).levels == t->mip_levels);
            }
        }
        if (config.technique != Technique::occlusion) {
            CHECK(layout.slice_map.empty());
            continue;
        }
        REQUIRE(layout.slice_map.size() == static_cast<std::size_t>(config.slices));
        for (const SliceLocation& at : layout.slice_map) {
            CAPTURE(at.slice);
            const TextureDesc* t = find_texture(layout, at.texture);
            REQUIRE(t);
            CHECK(channels(t->format) == 4);
            CHECK(at.layer < t->depth);
            // the slicing (or unpack) pass writes that texture and layer
            bool written = false;
            for (const PassDesc& pass : layout.passes)
                if (pass.program == "slicing" || pass.program == "unpack_slices")
                    for (const AttachmentDesc& out : pass.outputs)
                        written = written || (out.texture == at.texture && out.layer == at.layer);
            CHECK(written);
        }
    }
    CHECK(copies > 0);
    CHECK(mipmaps > 0);
}

// The compute prefilter (prefilter_stage compute): only when asked, its dispatch passes build every
// level above the packing pass exactly once, as images of the level's format, with the barrier the
// shading pass needs; the cost model counts them; every other combination is refused by name.
TEST_CASE("layout: the compute prefilter's dispatch passes, only when asked") {
    const Config fragment{.slices = 16, .resolution = 512};
    const Layout plain = describe_layout(fragment);
    for (const PassDesc& p : plain.passes) CHECK(p.action != PassAction::dispatch);
    for (const std::string& f : plain.files) CHECK(!f.ends_with(".comp"));
    CHECK(to_json(plain).find("\"prefilter_stage\"") == std::string::npos); // the default: not written

    Config config = fragment;
    config.prefilter_stage = PrefilterStage::compute;
    REQUIRE(is_valid(config));
    const Layout layout = describe_layout(config);
    CHECK(std::find(layout.files.begin(), layout.files.end(), "penumbra_nbuffer_levels.comp") != layout.files.end());
    std::vector<int> built; // levels the dispatches write, in order
    for (const PassDesc& p : layout.passes) {
        CHECK(p.program != "nbuffer_level");
        if (p.action != PassAction::dispatch) continue;
        CHECK(p.outputs.empty());
        CHECK(p.dispatch.local_size == std::array<int, 3>{16, 16, 1});
        CHECK(p.dispatch.memory_barrier ==
              std::vector<MemoryBarrierBit>{MemoryBarrierBit::texture_fetch, MemoryBarrierBit::texture_update});
        REQUIRE(p.inputs.size() == 1);
        const TextureDesc* source = find_texture(layout, p.inputs[0].texture);
        REQUIRE(source);
        const int tile = source->height, groups = (tile + 15) / 16;
        CHECK(p.dispatch.groups == std::array<int, 3>{4 * groups, groups, 1}); // T = 4 tiles side by side
        for (std::size_t i = 0; i < p.dispatch.images.size(); ++i) {
            const ImageBindingDesc& image = p.dispatch.images[i];
            CHECK(image.unit == static_cast<int>(i));
            CHECK(image.image == "penumbra_output" + std::to_string(i));
            CHECK(find_texture(layout, image.texture)->format == TextureFormat::rgba8);
            CHECK(image.access == ImageAccess::write_only);
            built.push_back(std::stoi(image.texture.substr(std::string("penumbra_level").size())));
        }
    }
    // levels 2 to 4 from level 1, 5 to 7 from level 4, 8 and 9 from level 7
    CHECK(built == std::vector<int>{2, 3, 4, 5, 6, 7, 8, 9});
    const std::string json = to_json(layout);
    CHECK(json.find("\"prefilter_stage\": \"compute\"") != std::string::npos);
    CHECK(json.find("\"action\": \"dispatch\"") != std::string::npos);
    CHECK(json.find("\"image_outputs\": [{\"image\": \"penumbra_output0\", \"texture\": \"penumbra_level2\"") !=
          std::string::npos);
    CHECK(json.find("\"dispatch\": {\"groups\": [128, 32, 1], \"local_size\": [16, 16, 1], \"memory_barrier\": "
                    "[\"TEXTURE_FETCH\", \"TEXTURE_UPDATE\"]}") != std::string::npos);

    // RGBA16F levels: rgba16f images
    Config half = config;
    half.level_format = LevelFormat::rgba16f;
    const Layout half_layout = describe_layout(half);
    for (const PassDesc& p : half_layout.passes)
        for (const ImageBindingDesc& image : p.dispatch.images)
            CHECK(find_texture(half_layout, image.texture)->format == TextureFormat::rgba16f);
    CHECK(to_json(half_layout).find("\"format\": \"RGBA16F\"") != std::string::npos);
    const Result<Emission> emitted = emit(half);
    REQUIRE(emitted.value);
    for (const Program& p : emitted.value->programs)
        if (p.name == "nbuffer_levels") CHECK(p.stages[0].text.find(", rgba16f) writeonly uniform image2D") != std::string::npos);

    // the cost model: each dispatch writes its levels once and reads its source level once
    const CostModel cost = cost_model(layout, 256, 256);
    long long written = 0, levels_bytes = 0;
    for (const PassCost& p : cost.passes)
        if (p.name.starts_with("nbuffer_levels_")) {
            written += p.bytes_written;
            CHECK(p.texel_fetches > 0);
            CHECK(p.bytes_read > 0);
        }
    for (int l = 2; l <= 9; ++l) {
        const TextureDesc* t = find_texture(layout, "penumbra_level" + std::to_string(l));
        REQUIRE(t);
        levels_bytes += 4LL * t->width * t->height;
    }
    CHECK(written == levels_bytes);
}

TEST_CASE("validate: the compute prefilter is refused outside N-buffers in the atlas on glsl450") {
    auto refusal = [](Config c) {
        c.prefilter_stage = PrefilterStage::compute;
        const std::vector<ConfigError> errors = validate(c);
        REQUIRE(errors.size() == 1);
        CHECK(errors[0].field == "prefilter_stage");
        CHECK(errors[0].message.find("allowed") != std::string::npos);
        return errors[0].message;
    };
    CHECK(refusal({.filter = Filter::mipmap}).find("N-buffer levels in the atlas only") != std::string::npos);
    CHECK(refusal({.filter = Filter::sat}).find("filter 'sat'") != std::string::npos);
    CHECK(refusal({.packing = Packing::array}).find("packing 'array'") != std::string::npos);
    CHECK(refusal({.filter = Filter::gaussian, .light = Light::sun}).find("filter 'gaussian'") != std::string::npos);
    for (Target target : {Target::glsl330, Target::essl300, Target::vulkan})
        CHECK(refusal({.resolution = 256, .target = target}).find("needs compute shaders") != std::string::npos);
    Config full{.slices = 16, .resolution = 512};
    full.level_reduction = -1; // every level at full resolution: level 9's taps 256 texels apart
    CHECK(refusal(full).find("level_reduction 0 to 4") != std::string::npos);
    full.level_bound = 5; // up to level 5 they fit
    full.prefilter_stage = PrefilterStage::compute;
    CHECK(is_valid(full));
    Config wide{.slices = 16, .resolution = 512};
    wide.level_reduction = 5;
    CHECK(refusal(wide).find("level_reduction 0 to 4") != std::string::npos);
    // the other techniques do not read it
    CHECK(is_valid({.technique = Technique::pcf, .prefilter_stage = PrefilterStage::compute}));
}

// solid_casters: the slicing program takes the per-draw flag penumbra_casterClosed, its pass an OR that
// the closed draws switch to XOR; refused where no logic op exists (and on the Vulkan runner); the default
// layout does not change.
TEST_CASE("solid casters: the per-draw flag, the OR pass, and the targets that refuse it") {
    Config config{.slices = 16, .resolution = 256};
    const Emission plain = *emit(config).value;
    config.solid_casters = true;
    REQUIRE(is_valid(config));
    const Emission solid = *emit(config).value;
    const PassDesc* slicing = nullptr;
    for (const PassDesc& p : solid.layout.passes)
        if (p.name == "slicing") slicing = &p;
    REQUIRE(slicing);
    CHECK(slicing->state.logic_op == LogicOp::bitwise_or);
    CHECK(!slicing->state.blend);
    bool flag = false;
    for (const ProgramDesc& p : solid.layout.programs)
        for (const ParamDesc& param : p.parameters)
            if (param.name == "penumbra_casterClosed") {
                flag = true;
                CHECK(p.name == "slicing");
                CHECK(param.source == UniformSource::draw);
            }
    CHECK(flag);
    CHECK(emit_file(config, "penumbra_slicing.frag").text.find("gl_FrontFacing ? k + 1.0 : k") != std::string::npos);
    CHECK(to_json(solid.layout).find("\"solid_casters\": true") != std::string::npos);
    CHECK(to_json(plain.layout).find("solid_casters") == std::string::npos); // absent means false
    for (Target target : {Target::essl300, Target::wgsl, Target::vulkan}) {
        Config refused = config;
        refused.target = target;
        refused.resolution = 128;
        const std::vector<ConfigError> errors = validate(refused);
        REQUIRE(errors.size() == 1);
        CHECK(errors[0].field == "solid_casters");
        CHECK(errors[0].message.find("logical XOR") != std::string::npos);
        CHECK(errors[0].message.find("allowed for") != std::string::npos);
    }
    config.target = Target::glsl330;
    config.resolution = 128;
    CHECK(is_valid(config));
    config.slices = 64; // the bits path: the closed draws toggle bit ranges
    config.target = Target::glsl450;
    REQUIRE(is_valid(config));
    CHECK(emit_file(config, "penumbra_slicing.frag").text.find("penumbra_slicesFrom(first)") != std::string::npos);
}

TEST_CASE("layout enums: every name round-trips, and the names are layout.json's words") {
    auto round_trips = [](auto values) {
        for (auto v : values) CHECK(parse_enum<decltype(v)>(to_string(v)) == v);
    };
    round_trips(all_values<TextureFormat>());
    round_trips(all_values<TextureTarget>());
    round_trips(all_values<TextureFilter>());
    round_trips(all_values<Wrap>());
    round_trips(all_values<CompareFunc>());
    round_trips(all_values<PassAction>());
    round_trips(all_values<Phase>());
    round_trips(all_values<BlendEquation>());
    round_trips(all_values<BlendFactor>());
    round_trips(all_values<LogicOp>());
    round_trips(all_values<MemoryBarrierBit>());
    CHECK(to_string(TextureFormat::depth32f) == "DEPTH_COMPONENT32F");
    CHECK(to_string(TextureTarget::texture_2d_array) == "2D_ARRAY");
    CHECK(to_string(LogicOp::bitwise_or) == "OR");
    CHECK_FALSE(parse_enum<PassAction>("draw"));
    // formats.hpp: one row per format
    for (TextureFormat f : all_values<TextureFormat>()) {
        CAPTURE(to_string(f));
        CHECK(bytes_per_texel(f) == channels(f) * bytes_per_channel(f));
        CHECK(is_depth(f) == to_string(f).starts_with("DEPTH_COMPONENT"));
        CHECK(is_integer(f) == to_string(f).ends_with("UI"));
        CHECK(channels(f) == (is_depth(f) ? 1 : to_string(f).starts_with("RGBA") ? 4 : to_string(f).starts_with("RG") ? 2 : 1));
    }
}

TEST_CASE("layout builder: designated initializers, bindings from the program, sampling from the texture") {
    // a layout as a technique folder builds it (detail/layout_builder.hpp's header comment)
    Layout layout;
    ProgramDesc blur{.name = "blur"};
    blur.parameters.push_back({.name = "penumbra_source", .type = "sampler2D", .binding = 3,
                               .filter = TextureFilter::nearest});
    layout.programs.push_back(blur);
    detail::LayoutBuilder b{layout};
    b.texture({.name = "moments", .format = TextureFormat::rgba16f, .width = 64, .height = 64,
               .min_filter = TextureFilter::linear, .mag_filter = TextureFilter::linear, .purpose = "moments"});
    b.texture({.name = "blurred", .format = TextureFormat::rgba16f, .width = 64, .height = 64, .purpose = "blurred"});
    b.pass({.name = "blur", .program = "blur", .inputs = {{"penumbra_source", "moments"}}, .outputs = {{"blurred"}},
            .viewport_width = 64, .viewport_height = 64});
    b.pass({.name = "copy", .action = PassAction::copy, .inputs = {{"", "blurred"}}, .outputs = {{"moments"}},
            .viewport_width = 64, .viewport_height = 64});
    detail::finish_sampling(layout);
    const PassDesc& pass = layout.passes.front();
    CHECK(pass.action == PassAction::fullscreen);
    CHECK(pass.phase == Phase::shadow);
    REQUIRE(pass.inputs.size() == 1);
    CHECK(pass.inputs[0].binding == 3);
    // the parameter's filter wins over the texture's; the wrap is the texture's
    CHECK(pass.inputs[0].sampling.min_filter == TextureFilter::nearest);
    CHECK(pass.inputs[0].sampling.wrap == Wrap::clamp_to_edge);
    CHECK_FALSE(pass.inputs[0].sampling.compare);
    REQUIRE(layout.programs[0].parameters[0].sampling); // no texture of its own: its first pass's sampling
    CHECK(*layout.programs[0].parameters[0].sampling == pass.inputs[0].sampling);
    CHECK(attachment_kind(layout, pass.outputs[0]) == AttachmentKind::color);
    CHECK(to_string(initial_contents(layout.textures[0])) == "zero");
    const CopyDesc copy = copy_region(layout.passes[1]);
    CHECK(copy.width == 64);
    CHECK(copy.target_layer == -1);
    CHECK(to_json(layout).find("\"copy\": {\"source_level\": 0, \"source_layer\": -1, \"target_level\": 0, "
                               "\"target_layer\": -1, \"width\": 64, \"height\": 64}") != std::string::npos);
}

// near_field: the slicing pass writes the slices' nearest depths into the T colour targets after the slices',
// penumbraVisibility reads them (nearest filtering) and caps the fused visibility with the unrolled rays;
// refused beyond 16 slices, with adaptive placement or solid casters, and on the targets without an emission
// of it.
TEST_CASE(
    "near field: the nearest depths after the slices, the rays in the visibility, and what refuses it") {
    Config config{.slices = 16, .resolution = 256};
    const Emission plain = *emit(config).value;
    config.near_field = true;
    REQUIRE(is_valid(config));
    const Emission near = *emit(config).value;
    const PassDesc* slicing = nullptr;
    for (const PassDesc& p : near.layout.passes)
        if (p.name == "slicing") slicing = &p;
    REQUIRE(slicing);
    REQUIRE(slicing->outputs.size() == 8);
    for (std::size_t t = 0; t < 4; ++t) {
        CHECK(slicing->outputs[t].texture == "penumbra_slices");
        CHECK(slicing->outputs[4 + t].texture == "penumbra_nearDepth");
        CHECK(slicing->outputs[4 + t].layer == static_cast<int>(t));
    }
    CHECK(slicing->state.blend_equation == BlendEquation::max); // the nearest surface of a slice wins
    const std::string frag = emit_file(config, "penumbra_slicing.frag").text;
    CHECK(frag.find("layout(location = 7) out vec4 penumbra_nearDepth3;") != std::string::npos);
    CHECK(frag.find("penumbra_nearDepth0 = vec4(equal(vec4(k), vec4(0.0, 1.0, 2.0, 3.0))) * near;") !=
          std::string::npos);
    const std::string visibility = emit_file(config, "penumbra_visibility.glsl").text;
    CHECK(visibility.find("uniform sampler2DArray penumbra_nearDepth;") != std::string::npos);
    CHECK(visibility.find("float penumbra_nearField(vec3 p, vec3 penumbra_clip)") != std::string::npos);
    std::size_t rays = 0, steps = 0;
    for (std::size_t at = 0; (at = visibility.find("// ray ", at)) != std::string::npos; ++at) ++rays;
    for (std::size_t at = 0;
         (at = visibility.find("blocked = max(blocked, penumbra_nearBlocked(", at)) != std::string::npos;
         ++at)
        ++steps;
    CHECK(rays == 9);
    CHECK(steps == 36);
    // the clip's part and the irradiance window's core: each fused visibility is capped by its own rays
    CHECK(visibility.find(", penumbra_nearField(p, penumbra_clip));") != std::string::npos);
    CHECK(emit_file(Config{.slices = 16, .resolution = 256}, "penumbra_visibility.glsl")
              .text.find("nearField") == std::string::npos);
    CHECK(to_json(near.layout).find("\"near_field\": true") != std::string::npos);
    CHECK(to_json(plain.layout).find("near_field") == std::string::npos); // absent means false
    auto refused = [&](Config c, std::string_view says) {
        const std::vector<ConfigError> errors = validate(c);
        REQUIRE(errors.size() == 1);
        CHECK(errors[0].field == "near_field");
        CHECK(errors[0].message.find(says) != std::string::npos);
    };
    Config c = config;
    c.slices = 32;
    refused(c, "at most 16 slices");
    c = config;
    c.slice_placement = SlicePlacement::adaptive;
    refused(c, "uniform slice placement");
    c = config;
    c.solid_casters = true;
    refused(c, "solid_casters");
    for (Target target : {Target::essl300, Target::wgsl, Target::vulkan, Target::hlsl}) {
        c = config;
        c.target = target;
        c.resolution = 128;
        refused(c, "desktop OpenGL only");
    }
    c = config;
    c.target = Target::glsl330;
    CHECK(is_valid(c));
}
