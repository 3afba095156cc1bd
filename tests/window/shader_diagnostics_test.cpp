// Driver logs as `file:line: message` with context, and medians for the timing summary.
#include "frame_stats.hpp"
#include "shader_diagnostics.hpp"

#include <doctest/doctest.h>

using namespace penumbra::playground;

TEST_CASE("diagnostics: Mesa's log after the runtime's file prefix, and already formatted lines") {
    const auto parsed =
        parse_shader_log("penumbra_deferred.frag: 0:12(5): error: syntax error, unexpected IDENTIFIER\n"
                         "0:14(1): error: `x' undeclared\n"
                         "other.vert:3: error: redefinition\n"
                         "link: error: no main\n");
    REQUIRE(parsed.size() == 4);
    CHECK(parsed[0].file == "penumbra_deferred.frag");
    CHECK(parsed[0].line == 12);
    CHECK(parsed[0].message == "error: syntax error, unexpected IDENTIFIER");
    CHECK(parsed[1].file == "penumbra_deferred.frag"); // the prefix carries over to the next lines
    CHECK(parsed[1].line == 14);
    CHECK(parsed[2].file == "other.vert");
    CHECK(parsed[2].line == 3);
    CHECK(parsed[3].file.empty());
    CHECK(parsed[3].message == "link: error: no main");
}

TEST_CASE("diagnostics: a few lines of context, the failing one marked") {
    const std::map<std::string, std::string> sources{{"a.frag", "l1\nl2\nl3\nl4\nl5\nl6\n"}};
    CHECK(format_diagnostic({"a.frag", 3, "error: bad"}, sources) ==
          "a.frag:3: error: bad\n     1 | l1\n     2 | l2\n>    3 | l3\n     4 | l4\n     5 | l5");
    CHECK(format_diagnostic({"a.frag", 6, "error: end"}, sources, 1) ==
          "a.frag:6: error: end\n     5 | l5\n>    6 | l6");
    CHECK(format_diagnostic({"", 0, "link failed"}, sources) == "link failed");
    CHECK(format_diagnostic({"missing.frag", 2, "error: x"}, sources) == "missing.frag:2: error: x");
}

TEST_CASE("median of frame times") {
    CHECK(median({}) == 0.0);
    CHECK(median({3.0}) == 3.0);
    CHECK(median({5.0, 1.0, 3.0}) == 3.0);
    CHECK(median({4.0, 1.0, 3.0, 2.0}) == 2.5);
    TimeSeries series;
    for (int i = 0; i < 300; ++i) series.add(i);
    CHECK(series.plot().size() == TimeSeries::plot_length);
    CHECK(series.plot().front() == 60.0f);
    CHECK(series.last() == 299.0);
}
