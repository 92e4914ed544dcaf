// Test cases for the skip mechanism's own test (skip_in_ctest_summary.cmake), hidden from
// discovery: each is run by name in a throw-away ctest project.
#include <catch2/catch.hpp>

#include "test_support.hpp"

TEST_CASE("probe: skips", "[.probe_skip]") {
  VT_SKIP("probe " << 1 << " needs nothing");
  FAIL("VT_SKIP must end the test case");
}

TEST_CASE("probe: passes", "[.probe_pass]") { CHECK(vt::test::kSkipExitCode != 0); }

TEST_CASE("probe: fails, then skips", "[.probe_fail_then_skip]") {
  CHECK(false);  // a failure before the skip must stay a failure
  VT_SKIP("too late");
}
