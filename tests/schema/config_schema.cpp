// config_schema.cpp — docs/layout.schema.json's "$defs" "config" object, the JSON Schema of
// layout.json's "config", is generated from the table of configuration fields
// (penumbra/config_fields.hpp): `--check FILE` fails when the file's differs (test "schema_config"),
// `--write FILE` puts the generated one in its place.
//
//   penumbra-config-schema --write docs/layout.schema.json
#include <penumbra/config_fields.hpp>

#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <string_view>

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

} // namespace

int main(int argc, char** argv) {
    const std::string mode = argc == 3 ? argv[1] : "";
    if (mode != "--check" && mode != "--write") {
        std::cerr << "error: usage: penumbra-config-schema --check|--write docs/layout.schema.json\n";
        return 2;
    }
    const std::string path = argv[2];
    std::ifstream in(path, std::ios::binary);
    std::stringstream read;
    read << in.rdbuf();
    std::string text = read.str();
    const auto [begin, end] = config_block(text);
    if (!in || begin == std::string::npos) {
        std::cerr << "error: " << path << ": cannot read it, or it has no \"$defs\" \"config\" object\n";
        return 2;
    }
    const std::string generated = penumbra::config_schema_json("    ");
    if (mode == "--check") {
        if (text.compare(begin, end - begin, generated) == 0) {
            std::cout << path << ": \"$defs\" \"config\" is the table's (" << penumbra::config_fields().size()
                      << " fields)\n";
            return 0;
        }
        std::cerr << "error: " << path << ": \"$defs\" \"config\" is not what the table of configuration fields "
                  << "(penumbra/config_fields.hpp) gives; allowed: the generated one (penumbra-config-schema --write "
                  << path << ")\n";
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
