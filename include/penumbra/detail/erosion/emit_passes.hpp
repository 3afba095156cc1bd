// penumbra/detail/erosion/emit_passes.hpp — the screen passes of the erosion technique (Klein et al.,
// "Contact Hardening Soft Shadows using Erosion"), each a full-screen fragment stage at the output size:
//   erosion_hard    hard shadow from the shadow map; blocker-receiver distance -> penumbra half-width
//                   in output pixels (parallel planes; pixel footprint from the world-position G-buffer)
//   erosion_edges   Laplacian of the hard shadow: edge pixels, with the penumbra half-width found there
//   erosion_reduce  min-max chain: level n+1 = max (edges, widths, hard) / min (hard) of level n
//   erosion_erode   variable-size erosion: the chain's coarsest level bounds the search radius, Poisson
//                   taps at the level matching their spacing find the nearest edge; its distance over
//                   the radius gives the visibility across the penumbra
//   erosion_blur    the paper's first solution: a blur over the penumbra's width
// Every texture value is in [0, 1] (widths divided by erosion.max_search_radius), so ES 3.0 can store
// them in RGBA8. Tap counts, offsets and radii are literals; taps are written out one by one.
#pragma once

#include "../shadow_map/emit_visibility.hpp"

namespace penumbra::detail {

inline constexpr std::string_view erosion_hard_texture = "penumbra_erosionHard";
inline constexpr std::string_view erosion_edges_texture = "penumbra_erosionEdges";
inline constexpr std::string_view erosion_penumbra_texture = "penumbra_erosionPenumbra";
inline constexpr std::uint64_t erosion_search_seed = 0xE505105ull;
inline constexpr std::uint64_t erosion_blur_seed = 0xB1C4ull;

// The screen passes only fetch texels (penumbra_fetch): no sampler on WGSL.
constexpr Param sampler_param(std::string_view name, std::string_view meaning) {
    return {Text(name), "sampler2D", meaning, "", Text(name), UniformSource::light, {}, /*fetch_only=*/true};
}

constexpr Param world_positions_param() {
    return {"penumbra_worldPositions", "sampler2D",
            "G-buffer: xyz world position, w = 1 where there is geometry and 0 for the background", "scene units",
            "penumbra_worldPositions", UniformSource::light, {}, /*fetch_only=*/true};
}

constexpr std::vector<Param> erosion_params(const Config& config, std::string_view program) {
    if (program == "erosion_hard") {
        std::vector<Param> params{light_from_world_param(), projection_param(config), depth_range_param()};
        params.push_back(uniform_param(config.light == Light::rect ? Uniform::light_size : Uniform::tan_angular_radius,
                                       config.light));
        // the shadow map itself, through a sampler without comparison
        params.push_back({"penumbra_shadowDepth", "sampler2D", "shadow map read as depth (no comparison)", "",
                          Text(shadow_map_texture), UniformSource::light, "NEAREST", /*fetch_only=*/false,
                          /*depth_texture=*/true});
        params.push_back(world_positions_param());
        return params;
    }
    if (program == "erosion_edges")
        return {sampler_param(erosion_hard_texture, "r: hard visibility, g: penumbra half-width / max radius, a: geometry")};
    if (program == "erosion_reduce")
        return {sampler_param(erosion_edges_texture, "the level being reduced (the pass binds one level)")};
    if (program == "erosion_erode")
        return {sampler_param(erosion_edges_texture, "min-max chain: r edge, g half-width / max radius, b min, a max"),
                sampler_param(erosion_hard_texture, "r: hard visibility, a: geometry")};
    return {sampler_param(erosion_penumbra_texture, "r: eroded visibility, g: search radius / max radius, b: geometry")};
}

constexpr double erosion_sqrt(double x) {
    if (x <= 0.0) return 0.0;
    double r = x < 1.0 ? 1.0 : x;
    for (int i = 0; i < 64; ++i) r = 0.5 * (r + x / r);
    return r;
}

constexpr Text erosion_title(std::string_view program) {
    if (program == "erosion_hard") return Text("erosion: hard shadow and penumbra half-width, fragment stage");
    if (program == "erosion_edges") return Text("erosion: Laplacian edges of the hard shadow, fragment stage");
    if (program == "erosion_reduce") return Text("erosion: min-max chain, level n to n+1, fragment stage");
    if (program == "erosion_erode") return Text("erosion: variable-size erosion, fragment stage");
    return Text("erosion: blur over the penumbra width (final visibility), fragment stage");
}

// `name`'s texel at p, clamped to the level: texelFetch outside a level is undefined.
constexpr void write_fetch_function(LineWriter& out, const Config& config) {
    out.chunk("fetch");
    out.line(signature(config, "vec4", "penumbra_fetch", {{"sampler2D", "s"}, {"ivec2", "p"}, {"int", "level"}}));
    out.line("{");
    const Text size = choose(is_wgsl(config), Text("vec2i(textureDimensions(s, level))"), Text("textureSize(s, level)"));
    out.line("return ", fetch(config, "s", cat("clamp(p, ", construct(config, "ivec2", "0"), ", ", size, " - 1)"), "level"), ";");
    out.line("}");
    out.blank();
}

// The output pixel under the fragment, as integer coordinates.
constexpr Text pixel_line(const Config& config) {
    return value(config, "ivec2", "pixel", construct(config, "ivec2", cat(frag_coord(config), ".xy")));
}

constexpr void write_hard_main(LineWriter& out, const Config& config) {
    const double max_r = config.erosion.max_search_radius;
    out.chunk("erosion_hard_main");
    out.line(main_signature(config));
    out.line("{");
    out.line(pixel_line(config));
    out.line(value(config, "vec4", "world", "penumbra_fetch(penumbra_worldPositions, pixel, 0)"));
    out.line("if (world.w < 0.5)");
    out.line("{");
    out.line("penumbra_out = vec4(1.0, 0.0, 0.0, 0.0);");
    out.line("return;");
    out.line("}");
    out.line(value(config, "vec4", "coord", "penumbra_shadowCoord(world.xyz)"));
    out.line(value(config, "float", "stored", sample_depth(config, "penumbra_shadowDepth", "coord.xy")));
    out.line(value(config, "float", "hard", conditional(config, "coord.z <= stored", "1.0", "0.0")));
    out.comment("footprint of the pixel on the receiver: the shortest step to a neighbouring geometry pixel");
    out.line(variable(config, "float", "footprint", "1e30"));
    out.line(variable(config, "vec4", "n"));
    for (const char* step : {"(1, 0)", "(-1, 0)", "(0, 1)", "(0, -1)"}) {
        out.line("// neighbour ivec2", step);
        out.line("n = penumbra_fetch(penumbra_worldPositions, pixel + ", type_name(config, "ivec2"), step, ", 0);");
        out.line(if_then(config, "n.w > 0.5", "footprint = min(footprint, distance(n.xyz, world.xyz));"));
    }
    out.line("footprint = ", conditional(config, "footprint < 1e29", "footprint", "1.0"), ";");
    out.comment("blocker-receiver distance along the light axis; parallel planes give the penumbra width");
    out.line(value(config, "vec2", "range", "penumbra_shadowDepthRange"));
    out.line(value(config, "float", "zBlocker", "max(range.x + stored * (range.y - range.x), 1e-4)"));
    out.line(value(config, "float", "gap", "max(coord.w - zBlocker, 0.0)"));
    if (config.light == Light::rect)
        out.line(value(config, "float", "width", "gap * 0.5 * (penumbra_lightSize.x + penumbra_lightSize.y) / zBlocker"));
    else
        out.line(value(config, "float", "width", "2.0 * gap * penumbra_tanAngularRadius"));
    out.line("// half-width in output pixels, stored over the largest search radius (", format_int(config.erosion.max_search_radius), " pixels)");
    out.line(value(config, "float", "halfWidth",
                   conditional(config, "hard > 0.5", "0.0",
                               cat("min(0.5 * width / footprint, ", format_float(max_r), ") * ", format_float(1.0 / max_r)))));
    out.line("penumbra_out = vec4(hard, halfWidth, 0.0, 1.0);");
    out.line("}");
}

constexpr void write_edges_main(LineWriter& out, const Config& config) {
    out.chunk("erosion_edges_main");
    out.line(main_signature(config));
    out.line("{");
    out.line(pixel_line(config));
    out.line(value(config, "vec4", "c", cat("penumbra_fetch(", erosion_hard_texture, ", pixel, 0)")));
    out.comment("4-neighbour Laplacian of the hard shadow; a background neighbour counts as the centre");
    out.line(variable(config, "float", "laplacian", "0.0"));
    out.line(variable(config, "float", "halfWidth", "c.g"));
    out.line(variable(config, "vec4", "n"));
    for (const char* step : {"(1, 0)", "(-1, 0)", "(0, 1)", "(0, -1)"}) {
        out.line("// neighbour ivec2", step);
        out.line("n = penumbra_fetch(", erosion_hard_texture, ", pixel + ", type_name(config, "ivec2"), step, ", 0);");
        out.line("laplacian += (", conditional(config, "n.a > 0.5", "n.r", "c.r"), ") - c.r;");
        out.line("halfWidth = max(halfWidth, ", conditional(config, "n.a > 0.5", "n.g", "0.0"), ");");
    }
    out.line(value(config, "float", "edge",
                   conditional(config, cat("c.a > 0.5 && abs(laplacian) > ", format_float(config.erosion.edge_threshold)),
                               "1.0", "0.0")));
    out.comment("r: edge, g: penumbra half-width at the edge, b: min and a: max of the hard shadow");
    out.line("penumbra_out = vec4(edge, edge * halfWidth, c.r, c.r);");
    out.line("}");
}

constexpr void write_reduce_main(LineWriter& out, const Config& config) {
    out.chunk("erosion_reduce_main");
    out.comment("level n is the sampler's only level; a 3x3 window over 2p..2p+2 also covers odd sizes");
    out.line(main_signature(config));
    out.line("{");
    out.line(value(config, "ivec2", "base", cat("2 * ", construct(config, "ivec2", cat(frag_coord(config), ".xy")))));
    out.line(variable(config, "vec4", "m", cat("penumbra_fetch(", erosion_edges_texture, ", base, 0)")));
    out.line(variable(config, "vec4", "t"));
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x) {
            if (x == 0 && y == 0) continue;
            out.line("// texel (", format_int(x), ", ", format_int(y), ")");
            out.line("t = penumbra_fetch(", erosion_edges_texture, ", base + ", type_name(config, "ivec2"), "(", format_int(x), ", ",
                     format_int(y), "), 0);");
            out.line("m = vec4(max(m.rg, t.rg), min(m.b, t.b), max(m.a, t.a));");
        }
    out.line("penumbra_out = m;");
    out.line("}");
}

constexpr void write_erode_main(LineWriter& out, const Config& config) {
    const ErosionParams& e = config.erosion;
    const int K = erosion_levels(e);
    const double max_r = e.max_search_radius;
    const std::vector<Tap> taps = poisson_disk(e.search_taps, erosion_search_seed);
    out.chunk("erosion_erode_main");
    out.line(main_signature(config));
    out.line("{");
    out.line(pixel_line(config));
    out.line(value(config, "vec4", "hard", cat("penumbra_fetch(", erosion_hard_texture, ", pixel, 0)")));
    out.line("if (hard.a < 0.5)");
    out.line("{");
    out.line("penumbra_out = vec4(1.0, 0.0, 0.0, 0.0);");
    out.line("return;");
    out.line("}");
    out.line("// coarsest chain level ", format_int(K), ": texels of ", format_int(1 << K),
             " pixels; the 3x3 around the pixel hold every edge within the search radius");
    out.line(value(config, "ivec2", "coarse", cat("pixel / ", format_int(1 << K))));
    out.line(variable(config, "vec4", "m", "vec4(0.0)"));
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) {
            out.line("// coarse texel (", format_int(x), ", ", format_int(y), ")");
            out.line("m = max(m, penumbra_fetch(", erosion_edges_texture, ", coarse + ", type_name(config, "ivec2"), "(",
                     format_int(x), ", ", format_int(y), "), ", format_int(K), "));");
        }
    out.comment("no edge in reach: the hard shadow is the answer (a real branch: the search is skipped)");
    out.line("if (m.r < 0.5)");
    out.line("{");
    out.line("penumbra_out = vec4(hard.r, 0.0, 1.0, 0.0);");
    out.line("return;");
    out.line("}");
    out.line(value(config, "float", "radius", cat("clamp(m.g * ", format_float(max_r), ", 1.0, ", format_float(max_r), ")")),
             " // pixels");
    out.comment("the chain level whose texels match the taps' spacing, so thin edges are not stepped over");
    out.line(value(config, "float", "spacing", cat("radius * ", format_float(erosion_sqrt(3.14159265358979 / e.search_taps)))));
    out.line(value(config, "int", "level",
                   cat("clamp(", construct(config, "int", "floor(log2(max(spacing, 1.0)))"), ", 0, ", format_int(K), ")")));
    out.line(value(config, "vec2", "centre", cat(construct(config, "vec2", "pixel"), " + 0.5")));
    out.line(variable(config, "float", "nearest",
                      conditional(config, cat("penumbra_fetch(", erosion_edges_texture, ", pixel, 0).r > 0.5"), "0.5", "radius")),
             " // an edge pixel: the edge lies half a pixel away");
    out.line(variable(config, "float", "e"));
    // WGSL shifts a vector by a vector of unsigned amounts
    const Text shift = choose(is_wgsl(config), Text(" >> vec2u(u32(level))"), Text(" >> level"));
    for (int i = 0; i < static_cast<int>(taps.size()); ++i) {
        if (i % 4 == 0)
            out.line("// search taps ", format_int(i), " to ",
                     format_int(i + 3 < static_cast<int>(taps.size()) ? i + 3 : static_cast<int>(taps.size()) - 1));
        const Tap& t = taps[static_cast<std::size_t>(i)];
        out.line("e = penumbra_fetch(", erosion_edges_texture, ", ",
                 construct(config, "ivec2", cat("centre + vec2(", format_float(t.x), ", ", format_float(t.y), ") * radius")),
                 shift, ", level).r;");
        out.line("nearest = min(nearest, ",
                 conditional(config, "e > 0.5", cat(format_float(erosion_sqrt(t.x * t.x + t.y * t.y)), " * radius"), "radius"),
                 ");");
    }
    out.comment("erosion: the penumbra is centred on the hard edge; 0.5 there, 0 or 1 a radius away");
    out.line(value(config, "float", "s", "0.5 * clamp(nearest / radius, 0.0, 1.0)"));
    out.line(value(config, "float", "visibility", conditional(config, "hard.r > 0.5", "0.5 + s", "0.5 - s")));
    out.line("penumbra_out = vec4(visibility, radius * ", format_float(1.0 / max_r), ", 1.0, 0.0);");
    out.line("}");
}

constexpr void write_blur_main(LineWriter& out, const Config& config) {
    const ErosionParams& e = config.erosion;
    const std::vector<Tap> taps = poisson_disk(e.blur_taps, erosion_blur_seed);
    out.chunk("erosion_blur_main");
    out.line(main_signature(config));
    out.line("{");
    out.line(pixel_line(config));
    out.line(value(config, "vec4", "c", cat("penumbra_fetch(", erosion_penumbra_texture, ", pixel, 0)")));
    out.comment("background, or no penumbra here: nothing to blur (a real branch)");
    out.line("if (c.b < 0.5 || c.g == 0.0)");
    out.line("{");
    out.line("penumbra_visibility = vec4(", conditional(config, "c.b < 0.5", "1.0", "c.r"), ");");
    out.line("return;");
    out.line("}");
    out.comment("half the penumbra half-width: smooths the erosion's steps without widening the penumbra");
    out.line(value(config, "float", "radius", cat("0.5 * c.g * ", format_float(static_cast<double>(e.max_search_radius)))));
    out.line(value(config, "vec2", "centre", cat(construct(config, "vec2", "pixel"), " + 0.5")));
    out.line(variable(config, "vec2", "sum", "vec2(c.r, 1.0)"), " // x: visibility, y: weight (geometry taps only)");
    out.line(variable(config, "vec4", "t"));
    for (int i = 0; i < static_cast<int>(taps.size()); ++i) {
        if (i % 4 == 0)
            out.line("// blur taps ", format_int(i), " to ",
                     format_int(i + 3 < static_cast<int>(taps.size()) ? i + 3 : static_cast<int>(taps.size()) - 1));
        const Tap& t = taps[static_cast<std::size_t>(i)];
        out.line("t = penumbra_fetch(", erosion_penumbra_texture, ", ",
                 construct(config, "ivec2", cat("centre + vec2(", format_float(t.x), ", ", format_float(t.y), ") * radius")),
                 ", 0);");
        out.line("sum += ", conditional(config, "t.b > 0.5", "vec2(t.r, 1.0)", "vec2(0.0)"), ";");
    }
    out.line("penumbra_visibility = vec4(sum.x / sum.y);");
    out.line("}");
}

// The fragment stage of erosion program `program`.
constexpr Text erosion_fragment(const Config& config, std::string_view program) {
    LineWriter out;
    write_preamble(out, config, erosion_title(program));
    out.line("// ", to_string(config.technique), ": search radius at most ", format_int(config.erosion.max_search_radius),
             " pixels, chain levels 0 to ", format_int(erosion_levels(config.erosion)), ", ",
             format_int(config.erosion.search_taps), " search / ", format_int(config.erosion.blur_taps), " blur taps");
    out.line(stage_variable(out, config, "out", 0, "vec4", program == "erosion_blur" ? "penumbra_visibility" : "penumbra_out", true));
    declare_builtin(out, config, true, "position", "vec4", frag_coord(config));
    out.blank();
    int binding = 0;
    write_params(out, config, erosion_params(config, program), "PenumbraPass", binding);
    write_fetch_function(out, config);
    if (program == "erosion_hard") {
        write_shadow_coord_function(out, config);
        write_hard_main(out, config);
    } else if (program == "erosion_edges") {
        write_edges_main(out, config);
    } else if (program == "erosion_reduce") {
        write_reduce_main(out, config);
    } else if (program == "erosion_erode") {
        write_erode_main(out, config);
    } else {
        write_blur_main(out, config);
    }
    write_entry_point(out, config, Stage::fragment);
    return out.take();
}

} // namespace penumbra::detail
