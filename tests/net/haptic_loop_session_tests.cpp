// The server with the real haptic loop (ServerConfig::loop): ticked at each pose's time on the
// pose history the server writes, on a manual clock shared by both ends.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <thread>

#include "vt/core/clock.hpp"
#include "vt/haptics/haptic_loop.hpp"
#include "vt/net/client.hpp"
#include "vt/net/server.hpp"
#include "vt/scene/demo_scene.hpp"
#include "session_constants.hpp"
#include "test_support.hpp"

using namespace vt;
using haptics::ActuatorFrame;

namespace {

// A 20 cm plate at y = 0 whose vibration map is the demo stripes pattern.
std::shared_ptr<const haptics::HapticScene> plateScene() {
  auto scene = std::make_shared<Scene>();
  scene->meshes.push_back(makePlane({0.2f, 0.2f}, 1));
  scene->vibrationMaps.push_back(makePatternVibrationMap(Pattern::Stripes, 128));
  Material material;
  material.vibrationMap = 0;
  material.physicalWidth_m = 0.2f;
  scene->materials.push_back(material);
  scene->objects.push_back({"plate", 0, 0, glm::mat4(1.0f)});
  return haptics::makeHapticScene(scene);
}

haptics::HapticConfig loopConfig() {
  haptics::HapticConfig config = haptics::HapticConfig::fiveFingertips();
  config.rate_hz = 250.0f;  // 32 samples per tick at 8 kHz
  config.tactile.model = haptics::TactileModelKind::TextureWaveform;
  config.sampling.timeout_ns = 0;
  return config;
}

// Index fingertip 2 mm into the plate, sliding along x at 0.1 m/s; other joints far above.
HandPose slide(std::uint64_t sequence, std::int64_t t_ns) {
  HandPose pose;
  pose.t_ns = t_ns;
  pose.sequence = sequence;
  pose.valid = true;
  for (auto& p : pose.position) p = glm::vec3(0.0f, 0.2f, 0.0f);  // within a hand's reach of the tip (the wire's range)
  for (auto& r : pose.radius_m) r = 0.008f;
  for (auto& q : pose.orientation) q = glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  pose.position[std::size_t(HandJoint::IndexTip)] = {-0.08f + 0.0004f * float(sequence), 0.006f, 0.0f};
  return pose;
}

bool anyNonzero(const ActuatorFrame& frame) {
  for (float v : frame.block[1])
    if (v != 0.0f) return true;
  return false;
}
}  // namespace

TEST_CASE("The server ticks the haptic loop at each pose's time and matches the loop run locally") {
  const auto scene = plateScene();
  vt::ManualClock clock(1'000'000'000);
  PoseHistory serverPoses;
  haptics::HapticLoop loop(loopConfig(), serverPoses, clock);
  SpscRing<ActuatorFrame> loopFrames(4);
  loop.addOutput(loopFrames);
  loop.publishScene(scene);
  net::ServerConfig serverConfig;
  serverConfig.bind = net::parseEndpoint("127.0.0.1:0");
  serverConfig.clock = &clock;
  serverConfig.poses = &serverPoses;  // the server writes it, the loop reads it
  serverConfig.tick = [&](std::int64_t t_ns, ActuatorFrame& frame) {
    loop.tickOnce(t_ns);
    while (loopFrames.pop(frame)) {
    }
  };
  net::Server server(serverConfig);
  server.start();
  PoseHistory clientPoses;
  SpscRing<ActuatorFrame> recorded(512);
  net::ClientConfig clientConfig;
  clientConfig.server = server.endpoint();
  clientConfig.codecs = {haptics::CodecId::RawFloat32};
  clientConfig.outputs.add(recorded);
  clientConfig.poses = &clientPoses;
  clientConfig.clock = &clock;
  clientConfig.pacePoses = false;  // lock-step: the test sends each pose
  net::Client client(clientConfig);
  client.connect();
  constexpr int kPoses = 100;
  for (int i = 1; i <= kPoses; ++i) {
    const std::int64_t t = 1'000'000'000 + std::int64_t(i) * kPeriod;
    clock.set(t);
    clientPoses.publish(slide(std::uint64_t(i), t));
    REQUIRE(client.sendPoseAt(t));
    REQUIRE(vt::test::eventually([&] { return client.stats().framesReceived == std::uint64_t(i); }));
  }
  clock.advance(kPeriod);
  REQUIRE(vt::test::eventually([&] { return client.stats().jitter.played == kPoses; }));
  client.disconnect();
  server.stop();

  // The same loop configuration run in this process on the same poses at the same times.
  PoseHistory localPoses;
  haptics::HapticLoop local(loopConfig(), localPoses, clock);
  SpscRing<ActuatorFrame> localFrames(512);
  local.addOutput(localFrames);
  local.publishScene(scene);
  std::map<std::uint64_t, ActuatorFrame> expected;
  for (int i = 1; i <= kPoses; ++i) {
    const std::int64_t t = 1'000'000'000 + std::int64_t(i) * kPeriod;
    localPoses.publish(slide(std::uint64_t(i), t));
    local.tickOnce(t);
    REQUIRE(localFrames.pop(expected[std::uint64_t(i)]));
  }
  ActuatorFrame frame;
  int compared = 0, nonzero = 0;
  double signal = 0, noise = 0;
  while (recorded.pop(frame)) {
    const auto it = expected.find(frame.sequence);
    if (it == expected.end() || frame.pose_t_ns == 0) continue;
    ++compared;
    nonzero += anyNonzero(frame) ? 1 : 0;
    for (int i = 0; i < 32; ++i) {
      const double ref = it->second.block[1][std::size_t(i)];
      const double d = ref - frame.block[1][std::size_t(i)];
      signal += ref * ref;
      noise += d * d;
    }
  }
  CHECK(compared == kPoses);  // lock-step on one clock: every frame on time
  CHECK(nonzero >= compared / 2);
  // Only the pose quantisation (0.02 mm steps) separates the two.
  CHECK(10.0 * std::log10(signal / std::max(noise, 1e-30)) >= 30.0);
  CHECK(server.stats().posesApplied == kPoses);
}
