// penumbra/static_glsl.hpp — emission in constant expressions.
//
//   constexpr penumbra::Config kShadows{.slices = 8, .resolution = 256};
//   constexpr std::string_view kVisibility =
//       penumbra::static_glsl<kShadows, "penumbra_visibility.glsl">;
//
// The text is computed by the compiler and stored in the program as a constant; it is the same
// text emit_file() returns at run time. An invalid configuration is a compile error whose
// template argument carries the validator's message (a file the configuration does not emit is
// one too: 'no_such_file<…{"penumbra_sat_pass.frag"}>'), e.g.
//   'penumbra::detail::invalid_configuration<…{"slices: 40 is out of range; allowed: 1 to 32, 64 or 128"}>'
//
// The emitter runs longer in a constant expression than compilers allow by default (the default
// configuration's snippet needs about 1.5 times GCC's 33,554,432 operations; Clang's 1,048,576 steps are
// far too few): the CMake target penumbra::penumbra raises the budget (-fconstexpr-ops-limit=268435456
// on GCC, -fconstexpr-steps=268435456 on Clang); without CMake, pass the same flag.
#pragma once

#include "detail/techniques.hpp"
#include "validate.hpp"

#include <array>
#include <cstddef>
#include <string_view>

namespace penumbra {
namespace detail {

// A string usable as a template argument, so a compile error can print it.
template <std::size_t N> struct FixedString {
    char text[N]{};
    constexpr FixedString() = default;
    constexpr FixedString(const char (&literal)[N]) {
        for (std::size_t i = 0; i < N; ++i) text[i] = literal[i];
    }
    constexpr std::size_t size() const { return N - 1; }
    constexpr std::string_view view() const { return {text, N - 1}; }
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

template <FixedString Name> struct no_such_file {
    static_assert(Name.size() == 0, "the configuration emits no file of this name (the template argument above)");
};

// The file named `name` among the configuration's files; its text function is null when there is none.
constexpr ShaderFileSpec find_file(const Config& config, std::string_view name) {
    for (const ShaderFileSpec& file : shader_files(config)) {
        const Text written_as = file_name(config, file.name); // a named Text: GCC 12 ends temporaries early here
        if (written_as.view() == name) return file;
    }
    return {};
}

// Text frozen into a null-terminated array: constexpr allocations cannot outlive constant
// evaluation, so the size is computed first and the characters copied into storage of that size.
template <Config C, FixedString Name> consteval auto frozen_text() {
    if constexpr (!is_valid(C)) {
        [[maybe_unused]] invalid_configuration<first_problem<C>()> error;
        return std::array<char, 1>{};
    } else if constexpr (find_file(C, Name.view()).text == nullptr) {
        [[maybe_unused]] no_such_file<Name> error;
        return std::array<char, 1>{};
    } else {
        constexpr std::size_t n = find_file(C, Name.view()).text(C).size();
        std::array<char, n + 1> out{};
        const Text text = find_file(C, Name.view()).text(C);
        for (std::size_t i = 0; i < n; ++i) out[i] = text.view()[i];
        return out;
    }
}

template <Config C, FixedString Name> inline constexpr auto frozen_text_v = frozen_text<C, Name>();

} // namespace detail

// The text of the file named Name (as layout.files names it) for configuration C, as a compile-time constant.
template <Config C, detail::FixedString Name>
inline constexpr std::string_view static_glsl{detail::frozen_text_v<C, Name>.data(), detail::frozen_text_v<C, Name>.size() - 1};

} // namespace penumbra
