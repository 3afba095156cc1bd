#include "arguments.hpp"
#include "cli.hpp"

#include <penumbra/validate.hpp>

#include <string_view>

namespace penumbra_gen {
namespace {

// Every flag, for the messages: the configuration flags, then the technique flags (technique_flags.cpp).
std::string flag_list() {
    return "--slices, --resolution, --filter, --fusion, --packing, --light, --target, --no-leak-fix, --no-fade, "
           "--tangent-clip, --no-tangent-clip, --slice-placement, --level-bound, --level-format, --level-reduction, "
           "--prefilter-stage, --tangent-clip-offset, --no-clip-footprint, --fade-ramp, --config, --validate, --out, "
           "--alpha-test, --help, " +
           std::string(technique_flag_list);
}

} // namespace

Parsed<Arguments> parse_arguments(const std::vector<std::string>& args) {
    if (penumbra::cli::asks_for_help(args)) {
        Arguments help;
        help.help = true;
        return {help, {}};
    }

    Arguments out;
    for (std::size_t i = 0; i < args.size(); ++i) {
        std::string_view arg = args[i];
        std::string_view flag = arg;
        std::optional<std::string_view> inline_value; // --flag=value
        if (arg.starts_with("--"))
            if (std::size_t eq = arg.find('='); eq != std::string_view::npos) {
                flag = arg.substr(0, eq);
                inline_value = arg.substr(eq + 1);
            }

        // Flags without a value.
        const bool is_switch = flag == "--no-leak-fix" || flag == "--no-fade" || flag == "--validate" ||
                               flag == "--tangent-clip" || flag == "--no-tangent-clip" || flag == "--no-clip-footprint" ||
                               flag == "--alpha-test" || is_technique_switch(flag);
        if (is_switch) {
            if (inline_value)
                return {{}, std::string(flag) + ": takes no value (got '" + printable(*inline_value) + "')"};
            if (flag == "--no-leak-fix") out.flags.no_leak_fix = true;
            if (flag == "--no-fade") out.flags.no_fade = true;
            if (flag == "--tangent-clip") out.flags.tangent_clip = true;
            if (flag == "--no-tangent-clip") out.flags.tangent_clip = false;
            if (flag == "--no-clip-footprint") out.flags.no_clip_footprint = true;
            if (flag == "--alpha-test") out.flags.alpha_test = true;
            if (flag == "--validate") out.validate = true;
            set_technique_switch(flag, out.flags.technique);
            continue;
        }
        const bool takes_value = flag == "--slices" || flag == "--resolution" || flag == "--filter" ||
                                 flag == "--fusion" || flag == "--packing" || flag == "--light" ||
                                 flag == "--target" || flag == "--slice-placement" || flag == "--level-bound" || flag == "--level-format" || flag == "--level-reduction" || flag == "--prefilter-stage" || flag == "--config" ||
                                 flag == "--tangent-clip-offset" || flag == "--fade-ramp" ||
                                 flag == "--out" ||
                                 is_technique_flag(flag);
        if (!takes_value) {
            if (arg.starts_with("-"))
                return {{}, "unknown flag '" + printable(flag) + "'; allowed: " + flag_list()};
            return {{},
                    "unexpected argument '" + printable(arg) +
                        "'; every value follows its flag (allowed flags: " + flag_list() + ")"};
        }
        std::string_view value;
        if (inline_value) {
            value = *inline_value;
        } else {
            if (i + 1 >= args.size()) return {{}, std::string(flag) + ": missing value (see --help)"};
            value = args[++i];
        }

        std::string error;
        if (flag == "--slices")
            error = parse_int(flag, value, out.flags.slices, penumbra::allowed_slices);
        else if (flag == "--resolution")
            error = parse_int(flag, value, out.flags.resolution, "a power of two from 32 to 4096");
        else if (flag == "--filter")
            error = parse_name(flag, value, out.flags.filter);
        else if (flag == "--fusion")
            error = parse_name(flag, value, out.flags.fusion);
        else if (flag == "--packing")
            error = parse_name(flag, value, out.flags.packing);
        else if (flag == "--light")
            error = parse_name(flag, value, out.flags.light);
        else if (flag == "--target")
            error = parse_name(flag, value, out.flags.target);
        else if (flag == "--slice-placement")
            error = parse_name(flag, value, out.flags.slice_placement);
        else if (flag == "--level-format")
            error = parse_name(flag, value, out.flags.level_format);
        else if (flag == "--prefilter-stage")
            error = parse_name(flag, value, out.flags.prefilter_stage);
        else if (flag == "--level-bound")
            error = parse_int(flag, value, out.flags.level_bound, "-1 (every level) or 0 to log2(resolution)");
        else if (flag == "--tangent-clip-offset")
            error = parse_real(flag, value, out.flags.tangent_clip_offset, "0 to 8 slicing texels");
        else if (flag == "--fade-ramp")
            error = parse_real(flag, value, out.flags.fade_ramp, "more than 0 to 4 (fraction of a slice's thickness)");
        else if (flag == "--level-reduction")
            error = parse_int(flag, value, out.flags.level_reduction,
                              "-1 (every level at full resolution) or 0 to log2(resolution)");
        else if (is_technique_flag(flag))
            error = parse_technique_flag(flag, value, out.flags.technique);
        else if (value.empty())
            error = std::string(flag) + ": empty path; allowed: a file or directory path";
        else if (flag == "--config")
            out.config_file = std::string(value);
        else
            out.out_dir = std::string(value); // --out
        if (!error.empty()) return {{}, error};
    }
    if (out.out_dir.empty()) return {{}, "--out: missing; the output directory is required (--out DIR)"};
    return {out, {}};
}

penumbra::Config apply(const ConfigFlags& flags, penumbra::Config config) {
    if (flags.slices) config.slices = *flags.slices;
    if (flags.resolution) config.resolution = *flags.resolution;
    if (flags.filter) config.filter = *flags.filter;
    if (flags.fusion) config.fusion = *flags.fusion;
    if (flags.packing) config.packing = *flags.packing;
    if (flags.light) config.light = *flags.light;
    if (flags.target) config.target = *flags.target;
    if (flags.no_leak_fix) config.leak_fix = false;
    if (flags.no_fade) config.self_shadow_fade = false;
    if (flags.tangent_clip) config.tangent_clip = *flags.tangent_clip;
    if (flags.slice_placement) config.slice_placement = *flags.slice_placement;
    if (flags.level_bound) config.level_bound = *flags.level_bound;
    if (flags.level_format) config.level_format = *flags.level_format;
    if (flags.tangent_clip_offset) config.tangent_clip_offset = *flags.tangent_clip_offset;
    if (flags.fade_ramp) config.fade_ramp = *flags.fade_ramp;
    if (flags.no_clip_footprint) config.clip_footprint = false;
    if (flags.level_reduction) config.level_reduction = *flags.level_reduction;
    if (flags.prefilter_stage) config.prefilter_stage = *flags.prefilter_stage;
    if (flags.alpha_test) config.alpha_test = true;
    return apply(flags.technique, config);
}

std::string usage() {
    using namespace penumbra;
    const Config d{};
    auto real = [](double v) { return penumbra::detail::format_float(v).str(); };
    auto line = [](std::string_view flag, std::string_view text) {
        std::string out = "  " + std::string(flag);
        out.resize(std::max<std::size_t>(out.size() + 1, 22), ' ');
        return out + std::string(text) + "\n";
    };
    auto names = [](std::string text, std::string_view def) {
        return text + " (default " + std::string(def) + ")";
    };
    std::string out = "usage: penumbra-gen [--technique T] [--slices N] [--resolution R] [--filter F] [--fusion U] "
                      "[--packing P] [--light L]\n"
                      "                    [--target T] [--no-leak-fix] [--no-fade] [--[no-]tangent-clip] [--slice-placement P]\n"
                      "                    [--level-bound N] [--level-format F] [--level-reduction N] [--prefilter-stage S]\n"
                      "                    [--tangent-clip-offset T] [--no-clip-footprint] [--fade-ramp F] [--alpha-test]\n"
                      "                    [technique flags] [--config FILE.json] [--validate] --out DIR\n"
                      "\n"
                      "Writes the GLSL of one Penumbra configuration and its layout.json into DIR.\n"
                      "\n"
                      "configuration (flags override the --config file):\n";
    out += line("--slices N",
                "slices along the light normal: " + std::string(penumbra::allowed_slices) + " (default " + std::to_string(d.slices) + ")");
    out += line("--resolution R", "occlusion texture side in texels: a power of two, 32 to 4096 (default " +
                                      std::to_string(d.resolution) + ")");
    out += line("--filter F", names("prefilter: " + allowed_names<Filter>(), to_string(d.filter)));
    out += line("--fusion U", names("slice fusion: " + allowed_names<Fusion>(), to_string(d.fusion)));
    out += line("--packing P", names("storage: " + allowed_names<Packing>(), to_string(d.packing)));
    out += line("--light L", names("area light: " + allowed_names<Light>(), to_string(d.light)));
    out += line("--target T", names("shading language: " + allowed_names<Target>(), to_string(d.target)));
    out += line("--no-leak-fix",
                std::string("turn off the leak fix (default ") + (d.leak_fix ? "on" : "off") + ")");
    out += line("--no-fade", std::string("turn off the self-shadow fade (default ") +
                                 (d.self_shadow_fade ? "on" : "off") + ")");
    out += line("--tangent-clip", std::string("kernels cover only the light above the receiver's tangent plane;\n"
                                              "                      penumbraVisibility takes the normal (default ") +
                                      (d.tangent_clip ? "on" : "off") + "; --no-tangent-clip turns it off)");
    out += line("--tangent-clip-offset T",
                "slicing texels by which the tangent clip moves a receiver sideways along its\n"
                "                      normal, off its own texels; 0 to 8 (default " + real(d.tangent_clip_offset) + ")");
    out += line("--no-clip-footprint", std::string("the tangent clip does not move receivers off their own footprint in the\n"
                                                   "                      slice above them (default ") +
                                           (d.clip_footprint ? "on" : "off") + ")");
    out += line("--fade-ramp F", "the self-shadow fade ramps over F of a slice's thickness; more than 0 to 4\n"
                                 "                      (default " + real(d.fade_ramp) + ")");
    out += line("--slice-placement P",
                names("slice boundaries: uniform (equal slices over the bounds) or adaptive (at the\n"
                      "                      depths the geometry occupies, computed on the GPU; paper §5)",
                      to_string(d.slice_placement)));
    out += line("--level-bound N", "highest filter level built and read: wider kernels read level N; the widest\n"
                                   "                      kernel of a light and scene is 2^N texels for the N of\n"
                                   "                      penumbra::kernel_level_bound; -1 or 0 to log2(resolution)\n"
                                   "                      (default -1: every level)");
    out += line("--level-format F", names("storage of the filtered levels: " + allowed_names<LevelFormat>() +
                                              "\n                      (essl300: always rgba8)",
                                          to_string(d.level_format)));
    out += line("--level-reduction N",
                "atlas of N-buffer or Gaussian levels: the levels above N are stored at half\n"
                "                      the resolution of the one below (level l at resolution / 2^(l - N));\n"
                "                      -1: every level at full resolution; 0 to log2(resolution)\n"
                "                      (default " + std::to_string(d.level_reduction) + ")");
    out += line("--prefilter-stage S",
                names("what builds the N-buffer levels above the packing pass: " + allowed_names<PrefilterStage>() +
                          "\n                      (compute: dispatches that build several levels each in shared memory;\n"
                          "                      filter nbuffer, packing atlas, target glsl450 only)",
                      to_string(d.prefilter_stage)));
    out += line("--alpha-test", std::string("cut-out casters, every technique: the passes that draw casters from the\n"
                                            "                      light discard fragments whose alpha (the draw's penumbra_alphaTexture\n"
                                            "                      at its penumbra_uv) is below its penumbra_alphaCutoff (default ") +
                                    (d.alpha_test ? "on" : "off") + ")");
    out += "\ntechnique (occlusion: the flags above; shadowmap, pcf, pcss, erosion, oim: these, plus --light and --target):\n";
    out += technique_usage(25);
    out +=
        line("--config FILE.json",
             "read the configuration from JSON: an object with the keys technique, slices, resolution,\n"
             "                      filter, fusion, packing, light, leak_fix, self_shadow_fade, tangent_clip,\n"
             "                      slice_placement, level_format, level_bound, level_reduction, prefilter_stage,\n"
             "                      tangent_clip_offset, clip_footprint, fade_ramp, target, alpha_test, and the objects\n"
             "                      shadow_map, pcf, pcss (all optional), or a\n"
             "                      layout.json, whose \"config\" object is read; a regular file of at most 1 MiB");
    out += "\noutput:\n";
    out += line("--out DIR", "directory to write into, created with its parents (required); all files or\n"
                             "                      none: on a failure the directory is left as it was. Files an\n"
                             "                      earlier run listed in DIR/layout.json that this one does not\n"
                             "                      write are removed");
    out +=
        line("--validate", "compile and link every program with glslang; on errors, print them, still write\n"
                           "                      the files (to inspect) and exit 1");
    out += line("--help, -h", "print this help and exit");
    out += "\nA value may also be given as --flag=value.\n"
           "exit status: 0 written; 1 glslang rejected the emitted code (files written); 2 bad arguments,\n"
           "configuration or output directory (nothing written); 3 internal error\n";
    return out;
}

} // namespace penumbra_gen
