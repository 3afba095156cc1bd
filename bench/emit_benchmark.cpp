// Prints how long run-time emission takes and how large the shading function is.
//
//   penumbra-bench-emit [iterations]
//
// Median over many calls of emit_file(config, visibility_snippet) and of a whole emit(config)
// (every file plus the layout); then the snippet size for 16 slices at 512² for each packing; then,
// for each technique that writes WGSL, a whole emit() for glsl450 and for wgsl, in the same run.
#include <penumbra/penumbra.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

template <class Work> double median_microseconds(int iterations, Work work) {
    std::vector<double> samples;
    samples.reserve(static_cast<std::size_t>(iterations));
    for (int i = 0; i < iterations; ++i) {
        const auto start = std::chrono::steady_clock::now();
        work();
        samples.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count());
    }
    std::nth_element(samples.begin(), samples.begin() + iterations / 2, samples.end());
    return samples[static_cast<std::size_t>(iterations / 2)];
}

} // namespace

int main(int argc, char** argv) {
    const int iterations = argc > 1 ? std::max(1, std::atoi(argv[1])) : 2000;
    std::size_t sink = 0;
    std::printf("%-44s %12s %12s\n", "configuration", "snippet us", "emit() us");
    for (penumbra::Packing packing : penumbra::all_values<penumbra::Packing>()) {
        const penumbra::Config config{.slices = 16, .resolution = 512, .packing = packing};
        const double snippet = median_microseconds(iterations, [&] {
            sink += penumbra::emit_file(config, "penumbra_visibility.glsl").text.size();
        });
        const double whole = median_microseconds(iterations / 10 + 1, [&] { sink += penumbra::emit(config).value->programs.size(); });
        std::printf("%-44s %12.1f %12.1f\n", ("16 slices, 512, nbuffer, " + std::string(penumbra::to_string(packing))).c_str(),
                    snippet, whole);
    }
    std::printf("\nshading function size, 16 slices at 512x512 (nbuffer / sat / mipmap)\n");
    std::printf("%-8s %-8s %10s %8s %14s\n", "packing", "filter", "bytes", "lines", "fn body lines");
    for (penumbra::Packing packing : penumbra::all_values<penumbra::Packing>())
        for (penumbra::Filter filter : {penumbra::Filter::nbuffer, penumbra::Filter::sat, penumbra::Filter::mipmap}) {
            const penumbra::Config config{.slices = 16, .resolution = 512, .filter = filter, .packing = packing};
            if (!penumbra::is_valid(config)) continue;
            const std::string text = penumbra::emit_file(config, "penumbra_visibility.glsl").text;
            const std::size_t body = text.find("\nfloat penumbraVisibility(");
            std::printf("%-8s %-8s %10zu %8ld %14ld\n", std::string(penumbra::to_string(packing)).c_str(),
                        std::string(penumbra::to_string(filter)).c_str(), text.size(),
                        std::count(text.begin(), text.end(), '\n'), std::count(text.begin() + body, text.end(), '\n'));
        }
    std::printf("\nGLSL against WGSL: a whole emit(), the technique's defaults\n");
    std::printf("%-10s %12s %12s %8s %12s %12s\n", "technique", "glsl450 us", "wgsl us", "ratio", "glsl bytes", "wgsl bytes");
    for (penumbra::Technique technique : penumbra::all_values<penumbra::Technique>()) {
        const penumbra::Config wgsl{.technique = technique, .target = penumbra::Target::wgsl};
        if (!penumbra::is_valid(wgsl)) continue;
        const penumbra::Config glsl{.technique = technique, .target = penumbra::Target::glsl450};
        const int runs = iterations / 10 + 1;
        auto whole = [&](const penumbra::Config& c) { sink += penumbra::emit(c).value->programs.size(); };
        whole(glsl), whole(wgsl); // warm-up
        const double g = median_microseconds(runs, [&] { whole(glsl); });
        const double w = median_microseconds(runs, [&] { whole(wgsl); });
        auto bytes = [](const penumbra::Config& c) {
            std::size_t n = 0;
            for (const penumbra::ShaderFile& f : penumbra::emit(c).value->files()) n += f.text.size();
            return n;
        };
        std::printf("%-10s %12.1f %12.1f %8.2f %12zu %12zu\n", std::string(penumbra::to_string(technique)).c_str(), g, w,
                    w / g, bytes(glsl), bytes(wgsl));
    }
    return sink == 0; // keeps the work observable
}
