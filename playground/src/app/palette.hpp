// palette.hpp — the one colour ramp of the playground's false-colour images: the error images
// (image_io.hpp: signed_error_colors, magnitude_colors; headless runs and the comparison
// benchmark) and the debug views' slice-level palette and error ramp (rendering/debug_views.cpp).
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <vector>

namespace penumbra::playground {

// Piecewise-linear colour ramp through evenly spaced stops; t in [0, 1], clamped.
template <std::size_t N> glm::vec3 ramp(const std::array<glm::vec3, N>& stops, float t) {
    t = std::clamp(t, 0.0f, 1.0f) * static_cast<float>(N - 1);
    const std::size_t i = std::min(static_cast<std::size_t>(t), N - 2);
    return glm::mix(stops[i], stops[i + 1], t - static_cast<float>(i));
}

// The colour of a value that is not a number, in every false-colour image.
inline constexpr glm::vec3 not_a_number_color{0.0f, 1.0f, 0.0f};

// Each value's colour on `stops` at ramp position to_t(value): 3 floats per value (RGB); NaN is
// not_a_number_color.
template <std::size_t N, class ToT>
std::vector<float> false_colors(std::span<const float> values, const std::array<glm::vec3, N>& stops, ToT to_t) {
    std::vector<float> out;
    out.reserve(values.size() * 3);
    for (float v : values) {
        const glm::vec3 c = std::isnan(v) ? not_a_number_color : ramp(stops, to_t(v));
        out.insert(out.end(), {c.r, c.g, c.b});
    }
    return out;
}

} // namespace penumbra::playground
