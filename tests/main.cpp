// doctest's main. Debian's doctest-dev ships no doctest_with_main library, so each test
// executable compiles this file once; the test files include <doctest/doctest.h> only.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
