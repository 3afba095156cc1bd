// config_schema.cpp — docs/layout.schema.json's "$defs" "config" object, the JSON Schema of
// layout.json's "config", is generated from the table of configuration fields
// (penumbra/config_fields.hpp): `--check FILE` fails when the file's differs (test "schema_config"),
// `--write FILE` puts the generated one in its place. The same table gives docs/configuration.md its
// reference of every field, between two marker lines: `--check-guide FILE` / `--write-guide FILE`
// (test "configuration_guide"), and cmake/PenumbraGenerate.cmake its keywords, one per flag of
// penumbra-gen: `--check-cmake FILE` / `--write-cmake FILE` (test "generate_flags"). A new field or
// technique edits none of these files by hand.
//
//   penumbra-config-schema --write docs/layout.schema.json
//   penumbra-config-schema --write-guide docs/configuration.md
//   penumbra-config-schema --write-cmake cmake/PenumbraGenerate.cmake
#include <penumbra/config_fields.hpp>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace {

// [begin, end) of the value of "$defs"."config" in the schema text, or npos when there is none: from
// its opening brace to the closing one at the same indentation (four spaces).
std::pair<std::size_t, std::size_t> config_block(const std::string& text) {
    constexpr std::size_t none = std::string::npos;
    const std::size_t defs = text.find("\n  \"$defs\": {");
    if (defs == none) return {none, none};
    const std::size_t key = text.find("\n    \"config\": {\n", defs);
    if (key == none) return {none, none};
    const std::size_t begin = text.find('{', key);
    const std::size_t close = text.find("\n    }", begin);
    if (close == none) return {none, none};
    return {begin, close + 6};
}

// The markers around the generated part of docs/configuration.md.
constexpr std::string_view guide_begin = "<!-- fields: generated from include/penumbra/config_fields.hpp by "
                                         "penumbra-config-schema --write-guide docs/configuration.md -->\n";
constexpr std::string_view guide_end = "<!-- end of the generated fields -->\n";

// The markers around the generated lists of cmake/PenumbraGenerate.cmake's penumbra_generate_flags().
constexpr std::string_view cmake_begin = "    # generated from the table of configuration fields by\n"
                                         "    # penumbra-config-schema --write-cmake cmake/PenumbraGenerate.cmake\n";
constexpr std::string_view cmake_end = "    # end of the generated flags\n";

// `flags` as CMake list lines of penumbra_generate_flags(): eight spaces in, wrapped before 110 columns.
std::string cmake_list(const std::string& variable, const std::vector<std::string>& flags) {
    std::string out = "    set(${" + variable + "}\n", line;
    for (const std::string& flag : flags) {
        if (!line.empty() && 8 + line.size() + 1 + flag.size() > 110) {
            out += "        " + line + "\n";
            line.clear();
        }
        line += (line.empty() ? "" : " ") + flag;
    }
    if (!line.empty()) out += "        " + line + "\n";
    return out + "        PARENT_SCOPE)\n";
}

// penumbra-gen's flags as penumbra_generate_shaders() takes them: those with a value (the fields' that
// are not true/false), then the switches (the true/false fields', "--[no-]x" as both, and --validate).
// --config and --out are its CONFIG and OUT_DIR.
std::string cmake_flags() {
    std::vector<std::string> values, switches;
    auto add = [](std::vector<std::string>& list, std::string flag) {
        if (std::find(list.begin(), list.end(), flag) == list.end()) list.push_back(std::move(flag));
    };
    for (const penumbra::ConfigField& f : penumbra::config_fields()) {
        if (f.flag.empty()) continue;
        if (f.kind != penumbra::FieldKind::boolean) {
            add(values, std::string(f.flag));
        } else if (f.flag.starts_with("--[no-]")) {
            add(switches, "--" + std::string(f.flag.substr(7)));
            add(switches, "--no-" + std::string(f.flag.substr(7)));
        } else {
            add(switches, std::string(f.flag));
        }
    }
    switches.push_back("--validate");
    return cmake_list("value_var", values) + cmake_list("switch_var", switches);
}

// One Markdown table a group of fields (every technique, then each technique's own): key, flag, what
// it allows, the default, what it means (the schema's longer description where a row has one).
std::string fields_markdown() {
    const penumbra::Config defaults{};
    auto cell = [](std::string_view text) {
        std::string out;
        for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
        return out;
    };
    // the groups in the order the table first names them, each with all of its rows
    std::vector<std::string> groups;
    auto group_of = [](const penumbra::ConfigField& f) {
        return f.techniques.empty() ? std::string("every technique") : penumbra::detail::technique_list(f);
    };
    for (const penumbra::ConfigField& f : penumbra::config_fields())
        if (std::find(groups.begin(), groups.end(), group_of(f)) == groups.end()) groups.push_back(group_of(f));
    std::string out;
    for (const std::string& group : groups) {
        out += (out.empty() ? "" : "\n") + std::string("### ") +
               (group == "every technique" ? "Every technique" : "Read by " + group) +
               "\n\n| key | flag | allowed | default | meaning |\n|---|---|---|---|---|\n";
        for (const penumbra::ConfigField& f : penumbra::config_fields()) {
            if (group_of(f) != group) continue;
            const std::string_view meaning = f.detail.empty() ? f.help : f.detail;
            out += "| `" + std::string(f.key) + "` | " +
                   (f.flag.empty() ? std::string("—") : "`" + std::string(f.flag) + "`") + " | " +
                   cell(penumbra::allowed_text(f)) + " | `" + penumbra::field_text(f, defaults) + "` | " + cell(meaning) +
                   " |\n";
        }
    }
    return out;
}

// The generated part of `text` at [begin, end): --check compares it with `generated`, --write puts
// `generated` in its place and writes the file. `part` names it in the messages ("\"$defs\" \"config\"
// is", "the fields are"), `write_flag` the mode that regenerates it.
int check_or_write(bool check, const std::string& path, std::string text, std::size_t begin, std::size_t end,
                   const std::string& generated, const std::string& part, const std::string& write_flag) {
    if (check) {
        if (text.compare(begin, end - begin, generated) == 0) {
            std::cout << path << ": " << part << " the table's (" << penumbra::config_fields().size() << " fields)\n";
            return 0;
        }
        std::cerr << "error: " << path << ": " << part << " not what the table of configuration fields "
                  << "(penumbra/config_fields.hpp) gives; allowed: the generated ones (penumbra-config-schema "
                  << write_flag << " " << path << ")\n";
        return 1;
    }
    text.replace(begin, end - begin, generated);
    std::ofstream out(path, std::ios::binary);
    out << text;
    if (!out) {
        std::cerr << "error: " << path << ": cannot write it\n";
        return 1;
    }
    std::cout << "wrote " << path << "\n";
    return 0;
}

// The part of `text` between the marker lines `first` and `last`: checked or written (`check`).
int marked_part(bool check, const std::string& path, const std::string& text, std::string_view first,
                std::string_view last, const std::string& generated, const std::string& part,
                const std::string& write_flag) {
    const std::size_t begin = text.find(first), end = text.find(last);
    if (begin == std::string::npos || end == std::string::npos || end < begin) {
        std::cerr << "error: " << path << ": no generated part (the marker lines are:\n" << first << last << ")\n";
        return 2;
    }
    return check_or_write(check, path, text, begin + first.size(), end, generated, part, write_flag);
}

} // namespace

int main(int argc, char** argv) {
    const std::string mode = argc == 3 ? argv[1] : "";
    const std::vector<std::string> modes{"--check", "--write", "--check-guide", "--write-guide", "--check-cmake",
                                         "--write-cmake"};
    if (std::find(modes.begin(), modes.end(), mode) == modes.end()) {
        std::cerr << "error: usage: penumbra-config-schema --check|--write docs/layout.schema.json, "
                     "--check-guide|--write-guide docs/configuration.md, or --check-cmake|--write-cmake "
                     "cmake/PenumbraGenerate.cmake\n";
        return 2;
    }
    const std::string path = argv[2];
    std::ifstream in(path, std::ios::binary);
    std::stringstream read;
    read << in.rdbuf();
    std::string text = read.str();
    if (!in) {
        std::cerr << "error: " << path << ": cannot read it\n";
        return 2;
    }
    if (mode.ends_with("-guide"))
        return marked_part(mode == "--check-guide", path, text, guide_begin, guide_end,
                           "\n" + fields_markdown() + "\n", "the fields are", "--write-guide");
    if (mode.ends_with("-cmake"))
        return marked_part(mode == "--check-cmake", path, text, cmake_begin, cmake_end, cmake_flags(),
                           "penumbra_generate_flags()'s lists are", "--write-cmake");
    const auto [begin, end] = config_block(text);
    if (begin == std::string::npos) {
        std::cerr << "error: " << path << ": it has no \"$defs\" \"config\" object\n";
        return 2;
    }
    return check_or_write(mode == "--check", path, text, begin, end, penumbra::config_schema_json("    "),
                          "\"$defs\" \"config\" is", "--write");
}
