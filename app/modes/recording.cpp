#include "modes/recording.hpp"

#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <deque>

#include "modes/touch_session.hpp"
#include "vt/core/error.hpp"

namespace vt::app {
namespace {
// The third field of a P record: bit 0 valid, bit 1 a new pose-history segment (a reset).
constexpr int kPoseJumpFlag = 2;
}  // namespace

SessionRecorder::SessionRecorder(const std::filesystem::path& path, const SceneOptions& scene,
                                 const HapticOptions& haptic)
    : m_path(path) {
  std::error_code ec;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
  m_out.open(path);
  if (!m_out) fail(path.string(), ": cannot create the recording file");
  m_out << kRecordingMagic << '\n' << "scene " << encodeSceneOptions(scene) << '\n';
  config(haptic);
}

void SessionRecorder::config(const HapticOptions& haptic) { m_out << "config " << encodeHapticOptions(haptic) << '\n'; }

void SessionRecorder::pose(const HandPose& pose, bool jump) {
  char number[32];
  m_out << "P " << pose.t_ns << ' ' << pose.sequence << ' ' << (int(pose.valid) | (jump ? kPoseJumpFlag : 0));
  auto put = [&](float v) {
    std::snprintf(number, sizeof number, " %.9g", double(v));
    m_out << number;
  };
  for (int j = 0; j < kHandJointCount; ++j) {
    const auto i = std::size_t(j);
    for (int k = 0; k < 3; ++k) put(pose.position[i][k]);
    for (int k = 0; k < 4; ++k) put(pose.orientation[i][k]);
    put(pose.radius_m[i]);
  }
  m_out << '\n';
}

void SessionRecorder::contact(const haptics::ContactTrace& t) {
  char line[200];
  std::snprintf(line, sizeof line, "C %lld %d %d %d %d %.9g %.9g %.9g %.9g\n", static_cast<long long>(t.t_ns),
                int(t.contact), int(t.inContact), t.inContact ? int(t.object) : -1, int(t.material), double(t.u),
                double(t.v), double(t.depth_m), double(t.intensity));
  m_out << line;
}

void SessionRecorder::frame(const haptics::ActuatorFrame& f) {
  // The loop's stop() emits a silent frame with no waveform block: a stop marker, not a tick.
  if (f.blockLength == 0) {
    m_out << "S " << f.t_ns << '\n';
    return;
  }
  char number[32];
  m_out << "F " << f.sequence << ' ' << f.t_ns << ' ' << f.pose_t_ns << ' ' << int(f.actuatorCount);
  for (int a = 0; a < f.actuatorCount; ++a) {
    std::snprintf(number, sizeof number, " %.9g", double(f.intensity[std::size_t(a)]));
    m_out << number;
  }
  m_out << '\n';
  ++m_frames;
}

void SessionRecorder::finish() {
  m_out.flush();
  if (!m_out) fail(m_path.string(), ": write failed (disk full?)");
  m_out.close();
}

namespace {

struct RecordedPose {
  HandPose pose;
  bool jump = false;
};

RecordedPose parsePose(std::istringstream& in, const std::string& where) {
  HandPose pose;
  int flags = 0;
  if (!(in >> pose.t_ns >> pose.sequence >> flags)) fail(where, ": pose: expected t_ns sequence flags");
  pose.valid = (flags & 1) != 0;
  for (int j = 0; j < kHandJointCount; ++j) {
    const auto i = std::size_t(j);
    for (int k = 0; k < 3; ++k) in >> pose.position[i][k];
    for (int k = 0; k < 4; ++k) in >> pose.orientation[i][k];
    in >> pose.radius_m[i];
  }
  if (!in) fail(where, ": pose: expected ", kHandJointCount, " joints of 8 numbers");
  return {pose, (flags & kPoseJumpFlag) != 0};
}

}  // namespace

ReplayResult replayRecording(const std::filesystem::path& path, const std::filesystem::path& outCsv) {
  std::ifstream in(path);
  if (!in) fail(path.string(), ": cannot open the recording");
  std::string line;
  if (!std::getline(in, line) || line != kRecordingMagic) {
    fail(path.string(), ": line 1: not a V-Touching recording (expected '", kRecordingMagic, "')");
  }
  std::ofstream csv;
  if (!outCsv.empty()) {
    csv.open(outCsv);
    if (!csv) fail(outCsv.string(), ": cannot create the replay output");
    csv << "sequence,t_ns";
    for (int a = 0; a < haptics::kMaxActuators; ++a) csv << ',' << haptics::actuatorName(haptics::ActuatorId(a));
    csv << '\n';
  }

  ReplayResult result;
  LoadedScene scene;
  SceneOptions sceneOptions;
  std::unique_ptr<TouchSession> session;
  haptics::ActuatorFrame replayed;
  std::deque<RecordedPose> pending;  // recorded poses not yet in the replay's history
  int lineNumber = 1;
  while (std::getline(in, line)) {
    ++lineNumber;
    const std::string where = str(path.string(), ": line ", lineNumber);
    if (line.empty() || line[0] == '#') continue;
    const auto space = line.find(' ');
    const std::string kind = line.substr(0, space);
    const std::string rest = space == std::string::npos ? std::string() : line.substr(space + 1);
    std::istringstream fields(rest);
    if (kind == "scene") {
      sceneOptions = decodeSceneOptions(rest, where);
      scene = loadScene(sceneOptions);
    } else if (kind == "config") {
      if (!scene.haptic) fail(where, ": config before the scene line");
      const HapticOptions options = decodeHapticOptions(rest, where);
      if (session) {
        session->setOptions(options);  // as live: a fresh loop, the same pose history
      } else {
        session = std::make_unique<TouchSession>(
            scene, TouchSessionSpec{.sceneOptions = sceneOptions, .haptic = options, .sinks = {.glove = "none"},
                                    .drive = TouchDrive::Stepped});
        session->onFrame([&](const haptics::ActuatorFrame& frame) { replayed = frame; });
      }
    } else if (kind == "P") {
      pending.push_back(parsePose(fields, where));
      ++result.poses;
    } else if (kind == "C") {
      ++result.contacts;
    } else if (kind == "S") {
      continue;  // the live loop stopped here (its silent frame); a config line may follow
    } else if (kind == "F") {
      if (!session) fail(where, ": actuator frame before the config line");
      std::uint64_t sequence = 0;
      std::int64_t t_ns = 0, pose_t_ns = 0;
      int count = 0;
      if (!(fields >> sequence >> t_ns >> pose_t_ns >> count) || count < 0 || count > haptics::kMaxActuators) {
        fail(where, ": frame: expected sequence t_ns pose_t_ns count(0..", haptics::kMaxActuators, ")");
      }
      std::array<float, haptics::kMaxActuators> recorded{};
      for (int a = 0; a < count; ++a) fields >> recorded[std::size_t(a)];
      if (!fields) fail(where, ": frame: expected ", count, " intensities");
      // The live history held every pose up to the newest one this tick saw (pose_t_ns).
      while (!pending.empty() && pending.front().pose.t_ns <= pose_t_ns) {
        session->publishPose(pending.front().pose, pending.front().jump);
        pending.pop_front();
      }
      HandPose newest;
      if (pose_t_ns != 0 && (!session->poses().newest(newest) || newest.t_ns != pose_t_ns))
        fail(where, ": frame uses pose t_ns=", pose_t_ns, " not in the recording");
      session->tick(t_ns);
      session->drain();
      double worst = 0.0;
      for (int a = 0; a < count; ++a) {
        worst = std::max(worst, std::abs(double(replayed.intensity[std::size_t(a)]) - double(recorded[std::size_t(a)])));
      }
      if (replayed.actuatorCount != count || worst > 1e-6) ++result.mismatches;
      result.maxDifference = std::max(result.maxDifference, worst);
      ++result.frames;
      if (csv) {
        csv << replayed.sequence << ',' << replayed.t_ns;
        for (int a = 0; a < haptics::kMaxActuators; ++a) csv << ',' << replayed.intensity[std::size_t(a)];
        csv << '\n';
      }
    } else {
      fail(where, ": unknown record '", kind, "' (expected scene, config, P, C, F or S)");
    }
  }
  if (!scene.haptic) fail(path.string(), ": no scene line");
  return result;
}

}  // namespace vt::app
