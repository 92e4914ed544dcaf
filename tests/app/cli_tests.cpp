// The option parser: finite numbers only, ranges named, repeated options refused; --hand.
#include <catch2/catch.hpp>

#include <stdexcept>

#include "cli.hpp"
#include "modes/hand_view.hpp"
#include "modes/haptic_options.hpp"
#include "test_support.hpp"
#include "vt/core/error.hpp"
#include "vt/scene/hand_mesh.hpp"

using Catch::Matchers::Contains;
using vt::cli::Args;

TEST_CASE("Numeric options refuse NaN, infinity and values out of range, naming the option", "[app][cli]") {
  for (const char* bad : {"nan", "NaN", "inf", "-inf", "infinity"}) {
    Args args("acquire", {"--length-mm", bad});
    REQUIRE_THROWS_WITH(args.doubleOr("length-mm", 100.0), Contains("--length-mm must be a finite number"));
  }
  Args huge("acquire", {"--scale", "1e400"});
  REQUIRE_THROWS_WITH(huge.doubleOr("scale", 2.5), Contains("--scale") && Contains("out of range"));
  Args big("acquire", {"--scale", "1e300"});
  REQUIRE_THROWS_WITH(big.doubleIn("scale", 2.5, 0.1, 100.0), Contains("--scale 1e+300 out of range 0.1..100"));
  Args fine("acquire", {"--scale=2.5", "--lines", "7"});
  CHECK(fine.doubleIn("scale", 2.5, 0.1, 100.0) == 2.5);
  CHECK(fine.intIn("lines", 50, 1, 2000) == 7);
  CHECK_NOTHROW(fine.finish());
}

TEST_CASE("An option or flag given twice is named as such", "[app][cli]") {
  REQUIRE_THROWS_WITH(Args("render", {"--gain", "1", "--gain=2"}), Contains("render: option --gain given more than once"));
  REQUIRE_THROWS_WITH(Args("acquire", {"--quiet", "x", "--quiet"}), Contains("option --quiet given more than once"));
  Args once("render", {"--out", "dir", "--fps", "3"});
  CHECK(once.value("out") == "dir");
  CHECK(once.doubleOr("fps", 30) == 3.0);
  Args outputs("run", {"--output", "audio", "--output=osc://127.0.0.1:9000"});  // repeatable by the table
  CHECK(outputs.values("output") == std::vector<std::string>{"audio", "osc://127.0.0.1:9000"});
}

TEST_CASE("The haptic pacing option reaches the loop's configuration, an unknown pacing is named", "[app][cli]") {
  Args spin("run", {"--haptic-pacing", "spin"});
  const vt::app::HapticOptions options = vt::app::readHapticOptions(spin);
  CHECK(options.pacing == vt::haptics::LoopPacing::Spin);
  CHECK(vt::app::makeHapticConfig(options).pacing == vt::haptics::LoopPacing::Spin);
  Args plain("run", {});
  CHECK(vt::app::readHapticOptions(plain).pacing == vt::haptics::LoopPacing::Sleep);
  Args busy("run", {"--haptic-pacing", "busy"});
  REQUIRE_THROWS_WITH(vt::app::readHapticOptions(busy), Contains("run: --haptic-pacing 'busy' is not sleep|spin"));
  // The loop thread's pacing: render and serve tick on their own threads' schedule.
  REQUIRE_THROWS_WITH(Args("render", {"--haptic-pacing", "spin"}), Contains("--haptic-pacing is for run"));
}

TEST_CASE("The option table decides what a command accepts", "[app][cli]") {
  REQUIRE_THROWS_WITH(Args("run", {"--trajectory", "x.csv"}),
                      Contains("run: option --trajectory is for render, client, not run (see vtouching help run)"));
  REQUIRE_THROWS_WITH(Args("run", {"--no-such-option"}), Contains("run: unknown option '--no-such-option'"));
  REQUIRE_THROWS_WITH(Args("run", {"--xr=yes"}), Contains("run: option --xr takes no value"));
  REQUIRE_THROWS_WITH(Args("render", {"--out"}), Contains("render: option --out needs a value"));
  // A value that looks like an option is still the value of the option before it.
  Args gain("render", {"--trajectory", "--odd-name.csv", "--gain", "-1"});
  CHECK(gain.value("trajectory") == "--odd-name.csv");
  CHECK(gain.value("gain") == "-1");
  // An option the command takes but whose form does not read it is named by finish().
  Args single("render", {"--out", "o", "--fps", "3"});
  CHECK(single.value("out") == "o");
  REQUIRE_THROWS_WITH(single.finish(), Contains("render: option --fps does not apply here"));
  Args extra("stats", {"a", "b"});
  CHECK(extra.positionals().size() == 2);
  CHECK_NOTHROW(extra.finish());
  Args left("stats", {"a"});
  REQUIRE_THROWS_WITH(left.finish(), Contains("stats: unexpected argument 'a'"));
}

TEST_CASE("Reading an option the table does not declare, or another default, is a bug", "[app][cli]") {
  Args args("run", {});
  CHECK_THROWS_AS(args.value("no-such-option"), std::logic_error);
  CHECK_THROWS_AS(args.value("xr"), std::logic_error);          // a flag read as a value
  CHECK_THROWS_AS(args.doubleOr("gain", 2.0), std::logic_error);  // the table says 1
  CHECK(args.doubleOr("gain", 1.0) == 1.0);
  CHECK_FALSE(args.value("trajectory"));  // another command's option: absent here, not read
  CHECK(args.readOptions().count("gain") == 1);
  CHECK(args.readOptions().count("trajectory") == 0);
  Args probe("run", {});
  probe.setProbe();
  CHECK_THROWS_AS(probe.finish(), vt::cli::ProbeDone);
}

TEST_CASE("The hand option picks the mesh or the skeleton, a hand model loads before any device", "[app][cli][hand]") {
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
