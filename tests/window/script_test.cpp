// The --script language: what parses, and the message for what does not.
#include "script.hpp"

#include <doctest/doctest.h>

using penumbra::playground::parse_script;

TEST_CASE("script: actions, arguments and numbers") {
    const auto parsed =
        parse_script("# a comment\n"
                     "set slices 8\n"
                     "\n"
                     "light 1 7.5 -2   # trailing comment\n"
                     "edit penumbra_deferred.frag replace vec3(visibility) => vec3(visibility * 0.5)\n"
                     "edit penumbra_deferred.frag append this is # not glsl\n"
                     "edit penumbra_deferred.frag replace ; =>\n"
                     "wait 3\n"
                     "wait_reload\n"
                     "screenshot out.png\n"
                     "answer overwrite\n");
    REQUIRE(parsed.error.empty());
    REQUIRE(parsed.actions.size() == 9);
    CHECK(parsed.actions[0].verb == "set");
    CHECK(parsed.actions[0].args == std::vector<std::string>{"slices", "8"});
    CHECK(parsed.actions[1].line == 4);
    CHECK(parsed.actions[1].numbers == std::vector<double>{1.0, 7.5, -2.0});
    CHECK(parsed.actions[2].args == std::vector<std::string>{"penumbra_deferred.frag", "replace",
                                                             "vec3(visibility)", "vec3(visibility * 0.5)"});
    CHECK(parsed.actions[3].args[2] == "this is # not glsl"); // '#' is text inside an edit
    CHECK(parsed.actions[4].args[2] == ";");
    CHECK(parsed.actions[4].args[3].empty());
    CHECK(parsed.actions[6].numbers.empty());
    CHECK(parsed.actions[7].args[0] == "out.png");
}

TEST_CASE("script: bad lines name the line, the problem and what is allowed") {
    struct Case {
        const char* text;
        const char* message;
    };
    const Case cases[] = {
        {"jump 3", "s.txt:1: unknown action 'jump'; allowed: set, light"},
        {"wait\n", "s.txt:1: wait takes 1 numbers, got 0"},
        {"set slices 8\nwait x", "s.txt:2: wait: 'x' is not a number"},
        {"light 1 2", "s.txt:1: light takes 3 numbers, got 2"},
        {"set slices", "s.txt:1: set takes KEY VALUE"},
        {"edit f.frag insert x", "s.txt:1: edit: unknown mode 'insert'; allowed: append, replace"},
        {"edit f.frag replace a b", "s.txt:1: edit FILE replace needs 'OLD => NEW'"},
        {"answer maybe", "s.txt:1: answer: 'maybe' is not allowed; allowed: overwrite, cancel"},
        {"wait -1", "s.txt:1: wait: -1 is out of range; allowed: a whole number of frames from 0 to 1000000"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.text);
        const auto parsed = parse_script(c.text, "s.txt");
        CHECK(parsed.actions.empty());
        CHECK(parsed.error.rfind(c.message, 0) == 0);
    }
}
