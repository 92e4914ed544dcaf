#include <catch2/catch.hpp>

#include <cmath>

#include "vt/core/error.hpp"
#include "vt/scene/trajectory.hpp"

using Catch::Matchers::Contains;

TEST_CASE("CSV trajectory interpolates palm position and curls between keys") {
  const vt::Trajectory t = vt::parseTrajectoryCsv(
      "# slide\nt_s,x_m,y_m,z_m,curl_index\n0,0,0.1,0,0\n1,0.2,0.1,0,1\n", "test.csv");
  REQUIRE(t.keys.size() == 2);
  CHECK(t.duration_s() == Approx(1.0));
  const vt::HandPose mid = t.poseAt(0.5);
  CHECK(mid.at(vt::HandJoint::Palm).x == Approx(0.1f));
  CHECK(mid.at(vt::HandJoint::Palm).y == Approx(0.1f));
  CHECK(mid.t_ns == 500'000'000);
  // Clamped outside the keys.
  CHECK(t.poseAt(-1.0).at(vt::HandJoint::Palm).x == Approx(0.0f));
  CHECK(t.poseAt(9.0).at(vt::HandJoint::Palm).x == Approx(0.2f));
  // The stamp is clamped with the pose: any time asked for converts (1e300 s was undefined).
  CHECK(t.poseAt(-1.0).t_ns == 0);
  CHECK(t.poseAt(1e300).t_ns == 1'000'000'000);
  CHECK(t.poseAt(std::nan("")).t_ns == 0);
  CHECK(t.poseAt(std::nan("")).at(vt::HandJoint::Palm).x == 0.0f);  // the first key's pose, not NaN
  // The index tip comes closer to the palm as the curl interpolates from 0 to 1.
  auto reach = [&](double time) {
    const vt::HandPose p = t.poseAt(time);
    return glm::distance(p.at(vt::HandJoint::IndexTip), p.at(vt::HandJoint::Palm));
  };
  CHECK(reach(0.5) < reach(0.0));
  CHECK(reach(1.0) < reach(0.5));
}

TEST_CASE("JSON trajectory with rotation and left hand") {
  const vt::Trajectory t = vt::parseTrajectoryJson(
      R"({"hand":"left","samples":[{"t_s":0,"palm_m":[0,0.1,0],"rotation_deg":[90,0,0]},{"t_s":2,"palm_m":[0,0.1,0.1]}]})",
      "test.json");
  CHECK(t.leftHand);
  const vt::HandPose p = t.poseAt(0.0);
  // Yaw 90 degrees turns the fingers from -Z to -X.
  CHECK(p.at(vt::HandJoint::MiddleTip).x < p.at(vt::HandJoint::Palm).x - 0.05f);
}

TEST_CASE("Malformed trajectories are rejected with the source and the problem") {
  REQUIRE_THROWS_WITH(vt::parseTrajectoryCsv("t_s,x_m,y_m\n0,0,0\n", "a.csv"), Contains("a.csv") && Contains("z_m"));
  REQUIRE_THROWS_WITH(vt::parseTrajectoryCsv("t_s,x_m,y_m,z_m\n0,0,0,0\n0,1,0,0\n", "b.csv"),
                      Contains("b.csv") && Contains("not after"));
  REQUIRE_THROWS_WITH(vt::parseTrajectoryCsv("t_s,x_m,y_m,z_m\n0,0,abc,0\n", "c.csv"),
                      Contains("line 2") && Contains("'abc'"));
  REQUIRE_THROWS_WITH(vt::parseTrajectoryCsv("t_s,x_m,y_m,z_m\n0,0,nan,0\n", "d.csv"), Contains("NaN"));
  REQUIRE_THROWS_WITH(vt::parseTrajectoryCsv("t_s,x_m,y_m,z_m,curl_ring\n0,0,0,0,2\n", "e.csv"),
                      Contains("outside 0..1"));
  REQUIRE_THROWS_WITH(vt::parseTrajectoryJson("{\"samples\":[{\"t_s\":0}]}", "f.json"), Contains("palm_m"));
  REQUIRE_THROWS_WITH(vt::parseTrajectoryJson("[1,2", "g.json"), Contains("not valid JSON"));
  REQUIRE_THROWS_WITH(vt::parseTrajectoryCsv("t_s,x_m,y_m,z_m\n", "h.csv"), Contains("no samples"));
  // Times whose nanosecond stamps would not fit 64 bits (found by fuzz_trajectory), either sign;
  // a Unix time still loads.
  REQUIRE_THROWS_WITH(
      vt::parseTrajectoryJson(R"({"samples":[{"t_s":1.7e39,"palm_m":[0,0.1,1]}]})", "i.json"),
      Contains("i.json") && Contains("sample 1") && Contains("beyond"));
  REQUIRE_THROWS_WITH(vt::parseTrajectoryCsv("t_s,x_m,y_m,z_m\n-1e10,0,0,0\n-9e9,0,0,0\n", "j.csv"),
                      Contains("j.csv") && Contains("beyond"));
  CHECK(vt::parseTrajectoryCsv("t_s,x_m,y_m,z_m\n1796000000,0,0,0\n1796000001,0,0,0\n", "k.csv").keys.size() == 2);
  REQUIRE_THROWS_WITH(vt::loadTrajectory("/nonexistent/path.csv"), Contains("path.csv': file not found"));
}
