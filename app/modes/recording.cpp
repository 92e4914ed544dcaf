#include "modes/recording.hpp"

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <type_traits>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <deque>

#include "modes/touch_pipeline.hpp"
#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/core/file_io.hpp"
#include "vt/scene/hand_mesh.hpp"

namespace vt::app {
namespace {
// The third field of a P record: bit 0 valid, bit 1 a new pose-history segment (a reset).
constexpr int kPoseJumpFlag = 2;
// Poses a replay holds until the actuator frame that saw them (~850 bytes each): live, a frame
// follows every few poses; a damaged file must not grow this without bound.
constexpr std::size_t kMaxPendingPoses = std::size_t(1) << 14;
}  // namespace

std::uint64_t recordingChecksum(std::string_view bytes, std::uint64_t hash) noexcept {
  for (const char c : bytes) hash = (hash ^ std::uint64_t(static_cast<unsigned char>(c))) * 0x100000001b3ull;
  return hash;
}

ReplayRecorder::ReplayRecorder(const std::filesystem::path& path, const SceneOptions& scene,
                                 const HapticOptions& haptic)
    : m_path(path) {
  std::error_code ec;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
  m_out = std::make_unique<OutputFile>(path);
  line(kRecordingMagic);
  line("scene " + encodeSceneOptions(scene));
  config(haptic);
}

void ReplayRecorder::remote(std::string_view server) { line("remote server=" + std::string(server)); }

void ReplayRecorder::line(std::string_view text) {
  m_out->write(text);
  m_out->write("\n");
  m_checksum = recordingChecksum("\n", recordingChecksum(text, m_checksum));
  ++m_lines;
}

void ReplayRecorder::config(const HapticOptions& haptic) { line("config " + encodeHapticOptions(haptic)); }

void ReplayRecorder::pose(const HandPose& pose, bool jump) {
  char number[32];
  std::ostringstream record;  // one line, checksummed as a whole by line()
  record << "P " << pose.t_ns << ' ' << pose.sequence << ' ' << (int(pose.valid) | (jump ? kPoseJumpFlag : 0));
  auto put = [&](float v) {
    std::snprintf(number, sizeof number, " %.9g", double(v));
    record << number;
  };
  for (int j = 0; j < kHandJointCount; ++j) {
    const auto i = std::size_t(j);
    for (int k = 0; k < 3; ++k) put(pose.position[i][k]);
    for (int k = 0; k < 4; ++k) put(pose.orientation[i][k]);
    put(pose.radius_m[i]);
  }
  line(record.str());
}

void ReplayRecorder::contact(const haptics::ContactTrace& t) {
  char text[200];
  std::snprintf(text, sizeof text, "C %lld %d %d %d %d %.9g %.9g %.9g %.9g", static_cast<long long>(t.t_ns),
                int(t.contact), int(t.inContact), t.inContact ? int(t.object) : -1, int(t.material), double(t.u),
                double(t.v), double(t.depth_m), double(t.intensity));
  line(text);
}

void ReplayRecorder::drawn(const DrawnFrame& frame, std::size_t contacts) {
  char number[32];
  std::ostringstream record;
  record << "D " << frame.display_t_ns << ' ' << frame.hand_t_ns << ' ' << contacts;
  for (std::size_t c = 0; c < contacts; ++c) {
    for (int k = 0; k < 3; ++k) {
      std::snprintf(number, sizeof number, " %.9g", double(frame.tip_m[c][k]));
      record << number;
    }
  }
  line(record.str());
}

void ReplayRecorder::frame(const haptics::ActuatorFrame& f) {
  // The loop's stop() emits a silent frame with no waveform block: a stop marker, not a tick.
  if (f.blockLength == 0) {
    line(str("S ", f.t_ns));
    return;
  }
  char number[32];
  std::ostringstream record;
  record << "F " << f.sequence << ' ' << f.t_ns << ' ' << f.pose_t_ns << ' ' << f.hand_t_ns << ' ' << int(f.actuatorCount);
  for (int a = 0; a < f.actuatorCount; ++a) {
    std::snprintf(number, sizeof number, " %.9g", double(f.intensity[std::size_t(a)]));
    record << number;
  }
  line(record.str());
  ++m_frames;
}

void ReplayRecorder::finish() {
  if (m_finished) return;
  m_finished = true;
  char end[64];
  std::snprintf(end, sizeof end, "E %llu %016llx\n", static_cast<unsigned long long>(m_lines),
                static_cast<unsigned long long>(m_checksum));
  m_out->write(end);
  m_out->commit();
}

namespace {

struct RecordedPose {
  HandPose pose;
  bool jump = false;
};

// The next field of a record as a number: a missing field, a word and NaN are each named as what
// they are (a NaN is not "a wrong count"). `what()` names the field, built only for an error.
template <class T, class What>
T number(std::istringstream& in, const std::string& where, What what) {
  std::string token;
  if (!(in >> token)) fail(where, ": ", what(), " is missing");
  const char* begin = token.c_str();
  char* end = nullptr;
  errno = 0;
  T value{};
  if constexpr (std::is_floating_point_v<T>) {
    value = T(std::strtod(begin, &end));
    if (end == begin + token.size() && std::isnan(value)) fail(where, ": ", what(), " is NaN");
    if (end == begin + token.size() && !std::isfinite(value)) fail(where, ": ", what(), " is infinite");
  } else if constexpr (std::is_signed_v<T>) {
    const long long wide = std::strtoll(begin, &end, 10);
    if (wide < std::numeric_limits<T>::min() || wide > std::numeric_limits<T>::max()) errno = ERANGE;
    value = T(wide);
  } else {
    value = T(std::strtoull(begin, &end, 10));
    if (token[0] == '-') errno = ERANGE;
  }
  if (end != begin + token.size()) fail(where, ": ", what(), " '", token, "' is not a number");
  if (errno == ERANGE) fail(where, ": ", what(), " ", token, " is out of range");
  return value;
}

// A fixed field name for number().
auto named(const char* name) {
  return [name] { return std::string(name); };
}

// A recorded time in nanoseconds, within the stamp budget: the loop, the pose history and the
// consistency meter subtract and offset them.
std::int64_t stamp(std::istringstream& in, const std::string& where, const char* name) {
  const auto t_ns = number<std::int64_t>(in, where, named(name));
  if (t_ns < -budget::kStampTime_ns || t_ns > budget::kStampTime_ns) {
    fail(where, ": ", name, " ", t_ns, " is beyond +-2^61 ns (73 years; docs/RELIABILITY.md)");
  }
  return t_ns;
}

RecordedPose parsePose(std::istringstream& in, const std::string& where) {
  HandPose pose;
  pose.t_ns = stamp(in, where, "pose t_ns");
  pose.sequence = number<std::uint64_t>(in, where, named("pose sequence"));
  const int flags = number<int>(in, where, named("pose flags"));
  pose.valid = (flags & 1) != 0;
  for (int j = 0; j < kHandJointCount; ++j) {
    const auto i = std::size_t(j);
    const auto joint = [j](const char* field, int k) {
      return [=] { return str("pose joint ", j, " (", handJointName(HandJoint(j)), ") ", field, k < 0 ? "" : str(" ", k)); };
    };
    for (int k = 0; k < 3; ++k) pose.position[i][k] = number<float>(in, where, joint("position", k));
    for (int k = 0; k < 4; ++k) pose.orientation[i][k] = number<float>(in, where, joint("orientation", k));
    pose.radius_m[i] = number<float>(in, where, joint("radius", -1));
  }
  if (std::string extra; in >> extra) fail(where, ": pose: more than ", kHandJointCount, " joints of 8 numbers");
  return {pose, (flags & kPoseJumpFlag) != 0};
}

/// An actuator frame as recorded (an F record): what the live loop output at one tick.
struct RecordedFrame {
  std::uint64_t sequence = 0;
  std::int64_t t_ns = 0;       // when the loop ticked
  std::int64_t pose_t_ns = 0;  // the newest pose its history held then (0: none)
  std::int64_t hand_t_ns = 0;  // the time it sampled the hand for
  int actuatorCount = 0;
  std::array<float, haptics::kMaxActuators> intensity{};
};

/// One record of a recording as read: its format checked, nothing loaded or run.
struct RecordingRecord {
  enum class Kind { Scene, Remote, Config, Pose, Contact, Drawn, Stop, Frame };
  Kind kind = Kind::Scene;
  std::string where;      // "FILE: line N", for what the replay finds wrong with it
  SceneOptions scene;     // Scene
  std::string server;     // Remote: the server a client's frames came from
  HapticOptions haptic;   // Config
  HandPose pose;          // Pose
  bool jump = false;      // Pose: it began a new pose-history segment
  RecordedFrame frame;    // Frame
};

/// Reads a recording record by record. Checks what the format promises: the header, the line
/// budget, each parsed record's fields, their order (one scene line, before any config; a config
/// before any frame) and the end record's line count and checksum. Throws vt::Error naming `name`
/// and the line.
class RecordingReader {
 public:
  /// Reads and checks the header line.
  RecordingReader(std::istream& in, std::string name);
  /// The next record; false at the end of the input after a verified end record (E).
  bool next(RecordingRecord& record);

 private:
  bool readLine();

  std::istream& m_in;
  std::string m_name, m_line;
  bool m_ended = false;  // a newline closed m_line
  std::uint64_t m_lineNumber = 0;  // a file of 2^31 empty lines is only 2 GB
  std::uint64_t m_checksum = recordingChecksum({});
  std::uint64_t m_frames = 0;
  bool m_scene = false, m_config = false, m_complete = false;
};

RecordingReader::RecordingReader(std::istream& in, std::string name) : m_in(in), m_name(std::move(name)) {
  readLine();
  if (m_line == "vtouching-recording 1" || m_line == "vtouching-recording 2") {
    fail(m_name, ": line 1: '", m_line, "' was recorded by an older version (without the hand times the replay "
         "needs); record it again");
  }
  if (!m_ended || m_line != kRecordingMagic) {
    fail(m_name, ": line 1: not a V-Touching recording (expected '", kRecordingMagic, "')");
  }
  m_checksum = recordingChecksum(m_line + "\n");
}

// The next line (without its newline) of at most the budget into m_line; false at the end of the
// input. m_ended tells whether a newline closed it (the last line of a cut file has none).
bool RecordingReader::readLine() {
  m_line.clear();
  m_ended = false;
  ++m_lineNumber;
  for (int c = m_in.get(); c != std::char_traits<char>::eof(); c = m_in.get()) {
    if (c == '\n') return m_ended = true;
    if (m_line.size() >= budget::kRecordingLineBytes) {
      fail(m_name, ": line ", m_lineNumber, ": longer than the limit of ", budget::kRecordingLineBytes, " bytes per line");
    }
    m_line.push_back(char(c));
  }
  return !m_line.empty();
}

bool RecordingReader::next(RecordingRecord& record) {
  using Kind = RecordingRecord::Kind;
  while (readLine()) {
    const std::string where = str(m_name, ": line ", m_lineNumber);
    if (m_complete) fail(where, ": data after the end record");
    if (!m_ended) fail(where, ": cut short (no newline): the recording is truncated; its end record (E) is missing");
    if (m_line.rfind("E ", 0) == 0) {
      unsigned long long lines = 0, sum = 0;
      if (std::sscanf(m_line.c_str(), "E %llu %llx", &lines, &sum) != 2) fail(where, ": end record: expected E LINES CHECKSUM");
      if (lines != m_lineNumber - 1) {
        fail(where, ": end record counts ", lines, " lines but ", m_lineNumber - 1, " precede it (lines lost or added)");
      }
      if (sum != m_checksum) fail(where, ": checksum mismatch: the recording was changed or damaged");
      m_complete = true;
      continue;
    }
    m_checksum = recordingChecksum("\n", recordingChecksum(m_line, m_checksum));
    if (m_line.empty() || m_line[0] == '#') continue;
    const auto space = m_line.find(' ');
    const std::string kind = m_line.substr(0, space);
    const std::string rest = space == std::string::npos ? std::string() : m_line.substr(space + 1);
    std::istringstream fields(rest);
    record.where = where;
    if (kind == "scene") {
      if (m_scene) fail(where, ": a second scene line (a recording holds one scene)");
      record.kind = Kind::Scene;
      record.scene = decodeSceneOptions(rest, where);
      m_scene = true;
    } else if (kind == "remote") {
      record.kind = Kind::Remote;
      record.server = rest.substr(rest.find('=') + 1);
    } else if (kind == "config") {
      if (!m_scene) fail(where, ": config before the scene line");
      record.kind = Kind::Config;
      record.haptic = decodeHapticOptions(rest, where);
      m_config = true;
    } else if (kind == "P") {
      record.kind = Kind::Pose;
      const RecordedPose pose = parsePose(fields, where);
      record.pose = pose.pose;
      record.jump = pose.jump;
    } else if (kind == "C") {
      record.kind = Kind::Contact;
    } else if (kind == "D") {
      record.kind = Kind::Drawn;  // a displayed frame: the consistency meter's, not the loop's
    } else if (kind == "S") {
      record.kind = Kind::Stop;   // the live loop stopped here (its silent frame); a config line may follow
    } else if (kind == "F") {
      if (!m_config) fail(where, ": actuator frame before the config line");
      record.kind = Kind::Frame;
      RecordedFrame& frame = record.frame;
      frame.sequence = number<std::uint64_t>(fields, where, named("frame sequence"));
      frame.t_ns = stamp(fields, where, "frame t_ns");
      frame.pose_t_ns = stamp(fields, where, "frame pose_t_ns");
      frame.hand_t_ns = stamp(fields, where, "frame hand_t_ns");
      frame.actuatorCount = number<int>(fields, where, named("frame actuator count"));
      if (frame.actuatorCount < 0 || frame.actuatorCount > haptics::kMaxActuators) {
        fail(where, ": frame: actuator count ", frame.actuatorCount, " is not in 0..", haptics::kMaxActuators);
      }
      frame.intensity = {};
      for (int a = 0; a < frame.actuatorCount; ++a)
        frame.intensity[std::size_t(a)] = number<float>(fields, where, [a] { return str("frame intensity ", a); });
      if (std::string extra; fields >> extra) fail(where, ": frame: more than ", frame.actuatorCount, " intensities");
      ++m_frames;
    } else {
      fail(where, ": unknown record '", kind, "' (expected scene, config, P, C, D, F or S)");
    }
    return true;
  }
  if (!m_scene) fail(m_name, ": no scene line");
  if (!m_complete) {
    fail(m_name, ": ends after line ", m_lineNumber - 1, " without its end record (E): the recording is truncated (",
         m_frames, " frames read)");
  }
  return false;
}

}  // namespace

ReplayResult replayRecording(const std::filesystem::path& path, const std::filesystem::path& outCsv,
                             const ReplayObserver& observer) {
  const LoadScope loading("recording '" + path.string() + "'");
  checkInputFile(path, "recording", std::numeric_limits<std::uintmax_t>::max());  // names a folder, a loop, ...
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(str("recording ", describeErrno(path, "read", errno ? errno : EIO)));
  return replayRecording(in, path.string(), loadScene, outCsv, observer);
}

ReplayResult replayRecording(std::istream& in, const std::string& name, const SceneLoader& load,
                             const std::filesystem::path& outCsv, const ReplayObserver& observer) {
  RecordingReader reader(in, name);
  std::unique_ptr<OutputFile> csv;
  if (!outCsv.empty()) {
    csv = std::make_unique<OutputFile>(outCsv);
    csv->write("sequence,t_ns");
    for (int a = 0; a < haptics::kMaxActuators; ++a) csv->write(str(',', haptics::actuatorName(haptics::ActuatorId(a))));
    csv->write("\n");
  }

  ReplayResult result;
  LoadedScene scene;
  SceneOptions sceneOptions;
  std::unique_ptr<TouchPipeline> pipeline;
  haptics::ActuatorFrame replayed;
  std::deque<RecordedPose> pending;  // recorded poses not yet in the replay's history
  RecordingRecord record;
  while (reader.next(record)) {
    const std::string& where = record.where;
    switch (record.kind) {
      case RecordingRecord::Kind::Scene:
        sceneOptions = record.scene;
        try {
          scene = load(sceneOptions);
        } catch (const Error& e) {
          fail(where, ": the scene it was recorded with: ", e.what());
        }
        break;
      case RecordingRecord::Kind::Remote:
        fail(where, ": a client's recording (its frames came from the server at ", record.server,
             "): there is no local haptic loop to replay; its P, C, F and D records are the consistency meter's inputs");
      case RecordingRecord::Kind::Config:
        if (pipeline) {
          pipeline->setOptions(record.haptic);  // as live: a fresh loop, the same pose history
        } else {
          pipeline = std::make_unique<TouchPipeline>(
              scene, TouchPipelineSpec{.sceneOptions = sceneOptions, .haptic = record.haptic, .sinks = {.glove = "none"},
                                      .drive = TouchDrive::Stepped});
          pipeline->onFrame([&](const haptics::ActuatorFrame& frame) { replayed = frame; });
          if (observer.started) observer.started(scene, *pipeline);
        }
        break;
      case RecordingRecord::Kind::Pose:
        if (pending.size() >= kMaxPendingPoses) {
          fail(where, ": more than ", kMaxPendingPoses, " poses without an actuator frame (the recording is damaged)");
        }
        pending.push_back({record.pose, record.jump});
        ++result.poses;
        break;
      case RecordingRecord::Kind::Contact:
        ++result.contacts;
        break;
      case RecordingRecord::Kind::Drawn:
      case RecordingRecord::Kind::Stop:
        break;
      case RecordingRecord::Kind::Frame: {
        const RecordedFrame& recorded = record.frame;
        // The live history held every pose up to the newest one this tick saw (pose_t_ns).
        while (!pending.empty() && pending.front().pose.t_ns <= recorded.pose_t_ns) {
          pipeline->publishPose(pending.front().pose, pending.front().jump);
          pending.pop_front();
        }
        HandPose newest;
        if (recorded.pose_t_ns != 0 && (!pipeline->poses().newest(newest) || newest.t_ns != recorded.pose_t_ns))
          fail(where, ": frame uses pose t_ns=", recorded.pose_t_ns, " not in the recording");
        pipeline->tick(recorded.t_ns, recorded.hand_t_ns);  // the hand's time as live (the display lag moved it)
        pipeline->drain();
        if (observer.ticked) observer.ticked(recorded.t_ns, *pipeline);
        double worst = 0.0;
        for (int a = 0; a < recorded.actuatorCount; ++a) {
          const auto i = std::size_t(a);
          worst = std::max(worst, std::abs(double(replayed.intensity[i]) - double(recorded.intensity[i])));
        }
        if (replayed.actuatorCount != recorded.actuatorCount || worst > 1e-6) ++result.mismatches;
        result.maxDifference = std::max(result.maxDifference, worst);
        ++result.frames;
        if (csv) {
          std::ostringstream row;
          row << replayed.sequence << ',' << replayed.t_ns;
          for (int a = 0; a < haptics::kMaxActuators; ++a) row << ',' << replayed.intensity[std::size_t(a)];
          row << '\n';
          csv->write(row.str());
        }
        break;
      }
    }
  }
  if (csv) csv->commit();
  return result;
}

}  // namespace vt::app
