// The test runner: Catch2's session, whose exit code also says "skipped" (VT_SKIP) to ctest.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "test_support.hpp"

int main(int argc, char* argv[]) { return vt::test::exitCode(Catch::Session().run(argc, argv)); }
