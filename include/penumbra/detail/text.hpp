// penumbra/detail/text.hpp — constexpr text building: a growable buffer, numbers, an indenting
// line writer.
//
// Why not std::string: GCC 12's constexpr std::string trips over its small-string buffer
// ("accessing _M_allocated_capacity instead of _M_local_buf"), and std::to_chars is not constexpr
// for floating point in C++20. The emitter must run in constant expressions, so it builds text in
// a std::vector<char> and turns it into std::string only at the run-time API boundary.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace penumbra::detail {

class Text {
public:
    constexpr Text() = default;
    constexpr Text(std::string_view text) : chars_(text.begin(), text.end()) {}
    constexpr Text(const char* text) : Text(std::string_view(text)) {}

    constexpr Text& operator+=(std::string_view text) {
        if (text.empty()) return *this; // GCC 12 -O3 warns (-Wnonnull) on inserting an empty range
        chars_.insert(chars_.end(), text.begin(), text.end());
        return *this;
    }
    constexpr Text& operator+=(char c) {
        chars_.push_back(c);
        return *this;
    }
    // Room for `n` characters in all: a text built from known parts grows once, not by doubling (constant
    // evaluation counts every character each reallocation copies).
    constexpr void reserve(std::size_t n) { chars_.reserve(n); }
    constexpr operator std::string_view() const { return view(); }
    constexpr std::string_view view() const { return {chars_.data(), chars_.size()}; }
    constexpr std::size_t size() const { return chars_.size(); }
    constexpr bool empty() const { return chars_.empty(); }
    std::string str() const { return std::string(view()); }

    friend constexpr bool operator==(const Text& a, const Text& b) { return a.view() == b.view(); }

private:
    std::vector<char> chars_;
};

// `when ? a : b` for Text. GCC 12 mishandles the lifetime of class temporaries chosen by the
// conditional operator in constant evaluation ("use of allocated storage after deallocation").
constexpr Text choose(bool when, Text a, Text b) {
    if (when) return a;
    return b;
}

// Concatenates anything that converts to std::string_view. Parts are taken by value: GCC 12 ends
// the life of Text temporaries passed by reference too early in constant evaluation.
template <class... Parts> constexpr Text cat(Parts... parts) {
    Text out;
    out.reserve((std::string_view(parts).size() + ... + 0));
    ((out += std::string_view(parts)), ...);
    return out;
}

constexpr Text format_int(long long value) {
    if (value == 0) return Text("0");
    const bool negative = value < 0;
    unsigned long long magnitude = negative ? 0ull - static_cast<unsigned long long>(value)
                                            : static_cast<unsigned long long>(value);
    char digits[24]{};
    int count = 0;
    while (magnitude > 0) {
        digits[count++] = static_cast<char>('0' + magnitude % 10);
        magnitude /= 10;
    }
    Text out;
    if (negative) out += '-';
    while (count > 0) out += digits[--count];
    return out;
}

// A GLSL float literal: fixed notation, up to twelve decimals (exact for every dyadic constant Penumbra bakes), trailing zeros dropped, always with
// a decimal point ("1.0", "0.0625"). Every constant Penumbra bakes is well inside ±1e6.
constexpr Text format_float(double value) {
    const bool negative = value < 0;
    const double magnitude = negative ? -value : value;
    constexpr unsigned long long scale = 1'000'000'000'000ull;
    const auto scaled = static_cast<unsigned long long>(magnitude * static_cast<double>(scale) + 0.5);
    const unsigned long long whole = scaled / scale;
    unsigned long long fraction = scaled % scale;
    Text out;
    if (negative && scaled != 0) out += '-';
    out += format_int(static_cast<long long>(whole));
    out += '.';
    if (fraction == 0) return out += '0', out;
    char decimals[12]{};
    for (int i = 11; i >= 0; --i) {
        decimals[i] = static_cast<char>('0' + fraction % 10);
        fraction /= 10;
    }
    int last = 11;
    while (decimals[last] == '0') --last;
    for (int i = 0; i <= last; ++i) out += decimals[i];
    return out;
}

// A value a WGSL or HLSL entry point passes in or out (detail/language.hpp): its attribute
// ("@location(0)", "@builtin(position)"; HLSL's semantic, "TEXCOORD0", "SV_Position"), the private
// global that holds it, the global's type, the type on the wire when it differs, and (HLSL) its
// location for Vulkan, -1 for a system value.
struct EntryVariable {
    Text attribute, name, type, wire_type;
    int location = -1;
};

// Writes shader text line by line with four-space indentation driven by braces.
class LineWriter {
public:
    // WGSL and HLSL: what the module's entry point (detail/language.hpp, write_entry_point) copies in,
    // returns, and calls before the body (WGSL's uniform blocks' loads). Empty for GLSL.
    std::vector<EntryVariable> entry_inputs, entry_outputs;
    std::vector<Text> entry_calls;

    constexpr void line(std::string_view text) {
        if (!text.empty() && text.front() == '}' && depth_ > 0) --depth_;
        if (!text.empty())
            for (int i = 0; i < depth_ * 4; ++i) out_ += ' ';
        out_ += text;
        out_ += '\n';
        if (!text.empty() && text.back() == '{') ++depth_;
    }
    // Joined in place rather than through cat(), which copies every part first: the unrolled tap lines
    // are most of a file's text, and constant evaluation counts every character copied.
    template <class... Parts> constexpr void line(const Parts&... parts) {
        Text joined;
        joined.reserve((std::string_view(parts).size() + ... + 0));
        ((joined += std::string_view(parts)), ...);
        line(joined.view());
    }
    constexpr void blank() { out_ += '\n'; }
    constexpr void comment(std::string_view text) { line("// ", text); }
    // Marks the start of a chunk so diagnostics can name the C++ emitter that wrote it
    // (see chunk_at_line in penumbra/program.hpp).
    constexpr void chunk(std::string_view name) { line("// @penumbra:", name); }
    // Fixed text (a raw string literal): every line re-indented relative to the current depth.
    constexpr void block(std::string_view text) {
        std::size_t start = (!text.empty() && text.front() == '\n') ? 1 : 0;
        while (start < text.size()) {
            std::size_t end = text.find('\n', start);
            if (end == std::string_view::npos) end = text.size();
            const std::string_view row = text.substr(start, end - start);
            const std::size_t first = row.find_first_not_of(' ');
            line(first == std::string_view::npos ? std::string_view{} : row.substr(first));
            start = end + 1;
        }
    }
    constexpr Text take() { return std::move(out_); }

private:
    Text out_;
    int depth_ = 0;
};

} // namespace penumbra::detail
