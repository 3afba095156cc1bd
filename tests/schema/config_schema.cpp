// config_schema.cpp — docs/layout.schema.json's "$defs" "config" object, the JSON Schema of
// layout.json's "config", is generated from the table of configuration fields
// (penumbra/config_fields.hpp): `--check FILE` fails when the file's differs (test "schema_config"),
// `--write FILE` puts the generated one in its place. The same table gives docs/configuration.md its
// reference of every field, between two marker lines: `--check-guide FILE` / `--write-guide FILE`
// (test "configuration_guide").
//
//   penumbra-config-schema --write docs/layout.schema.json
//   penumbra-config-schema --write-guide docs/configuration.md
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
        return f.techniques.empty() ? std::string("every technique") : std::string(f.techniques);
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

int guide(const std::string& mode, const std::string& path, std::string text) {
    const std::size_t begin = text.find(guide_begin), end = text.find(guide_end);
    if (begin == std::string::npos || end == std::string::npos || end < begin) {
        std::cerr << "error: " << path << ": no generated part (the marker lines are:\n" << guide_begin << guide_end << ")\n";
        return 2;
    }
    const std::size_t from = begin + guide_begin.size();
    return check_or_write(mode == "--check-guide", path, text, from, end, "\n" + fields_markdown() + "\n",
                          "the fields are", "--write-guide");
}

} // namespace

int main(int argc, char** argv) {
    const std::string mode = argc == 3 ? argv[1] : "";
    if (mode != "--check" && mode != "--write" && mode != "--check-guide" && mode != "--write-guide") {
        std::cerr << "error: usage: penumbra-config-schema --check|--write docs/layout.schema.json, or "
                     "--check-guide|--write-guide docs/configuration.md\n";
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
    if (mode.ends_with("-guide")) return guide(mode, path, text);
    const auto [begin, end] = config_block(text);
    if (begin == std::string::npos) {
        std::cerr << "error: " << path << ": it has no \"$defs\" \"config\" object\n";
        return 2;
    }
    return check_or_write(mode == "--check", path, text, begin, end, penumbra::config_schema_json("    "),
                          "\"$defs\" \"config\" is", "--write");
}
