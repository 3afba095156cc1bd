// doctest's main for the gl tests. Besides running them it
//   - prints what the run cost the driver: llvmpipe compiles every program with LLVM, so on a
//     machine whose shader cache is cold (MESA_SHADER_CACHE_DIR empty) the compiles and links, not
//     the rendering, are most of a part's time;
//   - fails a run whose filter selected no test case: each ctest part runs one file's cases by
//     --source-file, and a renamed file must not leave a part that passes having run nothing.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <penumbra/gl/link_program.hpp>

#include <cstdio>

namespace {

unsigned selected_test_cases = 0;

// Only test_run_end matters; doctest calls a listener's every hook.
struct SelectedCount : doctest::IReporter {
    explicit SelectedCount(const doctest::ContextOptions&) {}
    void report_query(const doctest::QueryData&) override {}
    void test_run_start() override {}
    void test_run_end(const doctest::TestRunStats& stats) override { selected_test_cases = stats.numTestCasesPassingFilters; }
    void test_case_start(const doctest::TestCaseData&) override {}
    void test_case_reenter(const doctest::TestCaseData&) override {}
    void test_case_end(const doctest::CurrentTestCaseStats&) override {}
    void test_case_exception(const doctest::TestCaseException&) override {}
    void subcase_start(const doctest::SubcaseSignature&) override {}
    void subcase_end() override {}
    void log_assert(const doctest::AssertData&) override {}
    void log_message(const doctest::MessageData&) override {}
    void test_case_skipped(const doctest::TestCaseData&) override {}
};
REGISTER_LISTENER("selected_count", 1, SelectedCount);

} // namespace

int main(int argc, char** argv) {
    doctest::Context context(argc, argv);
    const int result = context.run();
    if (context.shouldExit()) return result; // --help, --list-test-cases, ...
    const penumbra::gl::LinkCounts counts = penumbra::gl::link_counts();
    std::printf("gl programs: %ld shaders compiled, %ld programs linked (%.1f s), %ld of the links repeating a "
                "program linked before in this run\n",
                counts.compiles, counts.links, counts.seconds, counts.repeated_links);
    if (selected_test_cases == 0) {
        std::fprintf(stderr, "penumbra-tests-gl: the filter selected no test case (a part named after a file "
                             "that has none, or a misspelled --source-file / --test-case)\n");
        return 1;
    }
    return result;
}
