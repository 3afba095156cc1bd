// penumbra/static_glsl.hpp — emission in constant expressions.
//
//   constexpr penumbra::Config kShadows{.slices = 8, .resolution = 256};
//   constexpr std::string_view kVisibility =
//       penumbra::static_glsl<kShadows, penumbra::Artifact::visibility_snippet>;
//
// The text is computed by the compiler and stored in the program as a constant; it is the same
// text emit_file() returns at run time. An invalid configuration is a compile error whose
// template argument carries the validator's message, e.g.
//   'penumbra::detail::invalid_configuration<…{"slices: 40 is out of range; allowed: 1 to 32, 64 or 128"}>'
#pragma once

#include "detail/artifacts.hpp"
#include "validate.hpp"

#include <array>
#include <cstddef>
#include <string_view>

namespace penumbra {
namespace detail {

// A string usable as a template argument, so a compile error can print it.
template <std::size_t N> struct FixedString {
    char text[N]{};
    constexpr std::size_t size() const { return N - 1; }
};

template <Config C> consteval auto first_problem() {
    constexpr std::size_t n = find_problems(C).empty() ? 0 : find_problems(C).front().message.size();
    FixedString<n + 1> out{};
    if constexpr (n > 0) {
        const Text message = find_problems(C).front().message;
        for (std::size_t i = 0; i < n; ++i) out.text[i] = message.view()[i];
    }
    return out;
}

template <FixedString Message> struct invalid_configuration {
    static_assert(Message.size() == 0, "invalid penumbra::Config: the message is in the template argument above");
};

// Text frozen into a null-terminated array: constexpr allocations cannot outlive constant
// evaluation, so the size is computed first and the characters copied into storage of that size.
template <Config C, Artifact A> consteval auto frozen_text() {
    if constexpr (!is_valid(C)) {
        [[maybe_unused]] invalid_configuration<first_problem<C>()> error;
        return std::array<char, 1>{};
    } else {
        constexpr std::size_t n = artifact_text(C, A).size();
        std::array<char, n + 1> out{};
        const Text text = artifact_text(C, A);
        for (std::size_t i = 0; i < n; ++i) out[i] = text.view()[i];
        return out;
    }
}

template <Config C, Artifact A> inline constexpr auto frozen_text_v = frozen_text<C, A>();

} // namespace detail

// The text of artifact A for configuration C, as a compile-time constant.
template <Config C, Artifact A>
inline constexpr std::string_view static_glsl{detail::frozen_text_v<C, A>.data(), detail::frozen_text_v<C, A>.size() - 1};

} // namespace penumbra
