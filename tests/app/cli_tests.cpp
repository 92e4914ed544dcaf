// The option parser: finite numbers only, ranges named, repeated options refused; --hand.
#include <catch2/catch.hpp>

#include "cli.hpp"
#include "modes/hand_view.hpp"
#include "test_support.hpp"
#include "vt/core/error.hpp"
#include "vt/scene/hand_mesh.hpp"

using Catch::Matchers::Contains;
using vt::cli::Args;

TEST_CASE("Numeric options refuse NaN, infinity and values out of range, naming the option", "[app][cli]") {
  for (const char* bad : {"nan", "NaN", "inf", "-inf", "infinity"}) {
    Args args("acquire", {"--length-mm", bad});
    REQUIRE_THROWS_WITH(args.doubleOr("length-mm", 1.0), Contains("--length-mm must be a finite number"));
  }
  Args huge("acquire", {"--scale", "1e400"});
  REQUIRE_THROWS_WITH(huge.doubleOr("scale", 1.0), Contains("--scale") && Contains("out of range"));
  Args big("acquire", {"--scale", "1e300"});
  REQUIRE_THROWS_WITH(big.doubleIn("scale", 1.0, 0.1, 100.0), Contains("--scale 1e+300 out of range 0.1..100"));
  Args fine("acquire", {"--scale=2.5", "--lines", "7"});
  CHECK(fine.doubleIn("scale", 1.0, 0.1, 100.0) == 2.5);
  CHECK(fine.intIn("lines", 1, 1, 2000) == 7);
  CHECK_NOTHROW(fine.finish());
}

TEST_CASE("An option or flag given twice is named as such", "[app][cli]") {
  Args twice("render", {"--gain", "1", "--gain=2"});
  REQUIRE_THROWS_WITH(twice.value("gain"), Contains("render: option --gain given more than once"));
  Args flags("acquire", {"--quiet", "x", "--quiet"});
  REQUIRE_THROWS_WITH(flags.flag("quiet"), Contains("option --quiet given more than once"));
  Args once("render", {"--out", "dir", "--fps", "3"});
  CHECK(once.value("out") == "dir");
  CHECK(once.doubleOr("fps", 0) == 3.0);
}

TEST_CASE("The hand option picks the mesh or the skeleton; a hand model loads before any device", "[app][cli][hand]") {
  Args none("run", {});
  CHECK(vt::app::readHandViewOptions(none).style == vt::renderer::HandStyle::Mesh);
  Args skeleton("run", {"--hand", "skeleton"});
  const vt::app::HandViewOptions s = vt::app::readHandViewOptions(skeleton);
  CHECK(s.style == vt::renderer::HandStyle::Skeleton);
  CHECK_FALSE(s.model);
  Args bad("render", {"--hand=glove"});
  CHECK_THROWS_WITH(vt::app::readHandViewOptions(bad), Catch::Contains("--hand 'glove' is not mesh or skeleton"));
  const auto dir = vt::test::outputDir("cli_hand_model");
  vt::saveHandModel(vt::makeHandMesh(), dir / "hand.glb", true);
  Args both("run", {"--hand", "skeleton", "--hand-model", (dir / "hand.glb").string()});
  CHECK_THROWS_WITH(vt::app::readHandViewOptions(both), Catch::Contains("cannot go with --hand skeleton"));
  Args model("client", {"--hand-model", (dir / "hand.glb").string()});
  const vt::app::HandViewOptions m = vt::app::readHandViewOptions(model);
  REQUIRE(m.model);
  CHECK(m.model->mesh.vertices.size() == vt::makeHandMesh().mesh.vertices.size());
  Args missing("run", {"--hand-model", (dir / "none.glb").string()});
  CHECK_THROWS_WITH(vt::app::readHandViewOptions(missing), Catch::Contains("none.glb"));
}
