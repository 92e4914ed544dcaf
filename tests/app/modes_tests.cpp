// App modes without a window: offscreen trajectory runs, datasets, recording and replay.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <thread>

#include <catch2/catch.hpp>

#include "app_test_helpers.hpp"
#include "modes/touch_pipeline.hpp"
#include "modes/recording.hpp"
#include "modes/scene_source.hpp"
#include "modes/trajectory_run.hpp"
#include "test_support.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
#include "vt/scene/trajectory.hpp"

using namespace vt;
using namespace vt::test;

namespace {

// A slide across the middle of the first plate of `scene`, along x, from 5 % to 95 % of its width.
std::filesystem::path slideOverFirstPlate(const Scene& scene, const std::filesystem::path& file, double seconds) {
  const SceneObject& plate = scene.objects.at(0);
  const glm::vec3 centre(plate.T_world_object[3]);
  const Material& material = scene.materials.at(std::size_t(plate.material));
  const float half = material.physicalWidth_m * 0.45f;
  const float top = centre.y + 0.002f;  // dataset plates are 4 mm thick
  return writeIndexSlide(file, {centre.x - half, top, centre.z}, {centre.x + half, top, centre.z}, 0.003f, seconds);
}

// A one-plate band dataset under `out`, a 0.3 s slide over it, and where a session's recording goes.
struct RecordedSlide {
  explicit RecordedSlide(const std::filesystem::path& out) : recording(out / "session.txt") {
    sceneOptions.dataset = writeBandDataset(out / "dataset", "band", 100, 50, 0.4f, 0.6f, 0.5).string();
    scene = app::loadScene(sceneOptions);
    slide = loadTrajectory(slideOverFirstPlate(*scene.scene, out / "slide.csv", 0.3));
  }
  app::SceneOptions sceneOptions;
  app::LoadedScene scene;
  Trajectory slide;
  std::filesystem::path recording;
};

}  // namespace

TEST_CASE("Offscreen trajectory over a synthetic map peaks where the map is bright", "[app][trajectory]") {
  const auto out = outputDir("app_trajectory_band");
  const auto dataset = writeBandDataset(out / "dataset", "band", 200, 100, 0.6f, 0.7f, 0.5);
  app::TrajectoryRunOptions options;
  options.scene.dataset = dataset.string();
  const app::LoadedScene scene = app::loadScene(options.scene);
  options.trajectory = slideOverFirstPlate(*scene.scene, out / "slide.csv", 1.0);
  options.outDir = out / "run";
  options.fps = 4.0;
  options.width = 320;
  options.height = 180;
  options.validate = true;
  const app::TrajectoryRunResult result = app::runTrajectory(options);
  CHECK(result.validationMessages == 0);
  CHECK(result.framesWritten >= 4);
  CHECK(std::filesystem::exists(out / "run/figure.png"));
  CHECK(std::filesystem::exists(out / "run/figure_band.png"));
  CHECK(std::filesystem::exists(out / "run/figure_band.svg"));
  CHECK(std::filesystem::exists(out / "run/figure.svg"));
  CHECK_FALSE(std::filesystem::exists(out / "run/figure_table.png"));  // the table has no vibration map
  CHECK(std::filesystem::exists(out / "run/frame_00000.png"));

  const auto rows = readTraces(result.tracesCsv);
  double inBand = 0, outBand = 0;
  int nIn = 0, nOut = 0;
  const TraceRow* peak = nullptr;
  for (const TraceRow& r : rows) {
    if (r.finger != "index" || !r.contact || r.material != "band") continue;
    if (!peak || r.intensity > peak->intensity) peak = &r;
    // Away from the band edges (the 2 ms ramps and bilinear edges blur them).
    if (r.u > 0.62f && r.u < 0.68f) inBand += r.intensity, ++nIn;
    if (r.u < 0.55f || r.u > 0.75f) outBand += r.intensity, ++nOut;
  }
  REQUIRE(peak);
  REQUIRE(nIn > 20);
  REQUIRE(nOut > 100);
  CHECK(peak->u > 0.58f);
  CHECK(peak->u < 0.72f);
  CHECK(inBand / nIn > 4.0 * (outBand / nOut));
  // The other fingers stay off the plate (only the index finger is lowered).
  CHECK(std::none_of(rows.begin(), rows.end(), [](const TraceRow& r) { return r.finger == "ring" && r.contact; }));
}

TEST_CASE("Offscreen trajectory runs are deterministic", "[app][trajectory]") {
  const auto out = outputDir("app_trajectory_repeat");
  const auto dataset = writeBandDataset(out / "dataset", "band", 100, 50, 0.3f, 0.5f, 0.5);
  app::TrajectoryRunOptions options;
  options.scene.dataset = dataset.string();
  options.fps = 0.0;
  options.haptic.model = haptics::TactileModelKind::TextureWaveform;
  const app::LoadedScene scene = app::loadScene(options.scene);
  options.trajectory = slideOverFirstPlate(*scene.scene, out / "slide.csv", 0.5);
  options.outDir = out / "a";
  app::runTrajectory(options);
  options.outDir = out / "b";
  app::runTrajectory(options);
  auto slurp = [](const std::filesystem::path& p) {
    std::ifstream in(p);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string a = slurp(out / "a/traces.csv");
  CHECK(a.size() > 10000);
  CHECK(a == slurp(out / "b/traces.csv"));
}

TEST_CASE("Dataset mode on the published Pixel2Taxel data", "[app][dataset]") {
  const auto dir = datasetDir();
  if (!dir) VT_SKIP("published dataset not present");
  const auto out = outputDir("app_dataset");
  app::TrajectoryRunOptions options;
  options.scene.dataset = dir->string();
  const app::LoadedScene scene = app::loadScene(options.scene);
  REQUIRE(scene.scene->objects.size() == 9);  // eight plates and the table
  CHECK(scene.description.find("(8 objects") != std::string::npos);  // the table is not counted
  CHECK(scene.scene->vibrationMaps.size() == 8);
  options.trajectory = slideOverFirstPlate(*scene.scene, out / "slide.csv", 1.0);
  options.outDir = out / "run";
  options.fps = 0.0;
  const app::TrajectoryRunResult result = app::runTrajectory(options);
  CHECK(result.peakIntensity > 0.05f);
  const std::string first = scene.scene->objects[0].name;
  const auto rows = readTraces(result.tracesCsv);
  CHECK(std::count_if(rows.begin(), rows.end(), [&](const TraceRow& r) { return r.contact && r.material == first; }) > 500);
  CHECK(std::filesystem::exists(out / ("run/figure_" + first + ".png")));
}

TEST_CASE("A live run's recording replays to the same actuator output", "[app][replay]") {
  const auto out = outputDir("app_replay");
  const RecordedSlide setup(out);
  const auto& [sceneOptions, scene, slide, recording] = setup;
  {
    app::HapticOptions haptic;
    app::TouchPipeline pipeline(scene, {.sceneOptions = sceneOptions, .haptic = haptic,
                                      .sinks = {.glove = "sim", .record = recording.string()}});
    // Poses at ~100 Hz from this thread while the loop ticks on its own, as in the desktop mode.
    const std::int64_t start = SteadyClock::instance().now_ns();
    for (int i = 0; i < 60; ++i) {
      HandPose pose = slide.poseAt(slide.duration_s() * i / 59.0);
      pose.t_ns = SteadyClock::instance().now_ns();
      pipeline.publishPose(pose);
      if (i == 30) {  // a settings change restarts the loop mid-recording
        app::HapticOptions changed = haptic;
        changed.model = haptics::TactileModelKind::TextureWaveform;
        pipeline.setOptions(changed);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      pipeline.drain();
    }
    pipeline.stop();
    INFO("session ran " << (SteadyClock::instance().now_ns() - start) / 1000000 << " ms");
  }
  const app::ReplayResult r = app::replayRecording(recording, out / "replayed.csv");
  CHECK(r.frames > 100);
  CHECK(r.poses == 60);
  CHECK(r.mismatches == 0);
  CHECK(r.maxDifference == 0.0);

  // A changed output value in the file is found.
  std::ifstream in(recording);
  std::string text(std::istreambuf_iterator<char>(in), {});
  const auto frame = text.find("\nF ");
  REQUIRE(frame != std::string::npos);
  const auto lineEnd = text.find('\n', frame + 1);
  char& digit = text[lineEnd - 1];  // the last intensity's last digit
  digit = digit == '7' ? '3' : '7';
  std::ofstream(out / "tampered.txt") << text;
  CHECK_THROWS_WITH(app::replayRecording(out / "tampered.txt"), Catch::Contains("checksum mismatch"));
  // With its checksum made to match again, the changed value is what replay finds.
  const auto end = text.rfind("\nE ") + 1;
  const std::string body = text.substr(0, end);
  std::ofstream(out / "resealed.txt") << body << "E " << std::count(body.begin(), body.end(), '\n') << ' ' << std::hex
                                      << app::recordingChecksum(body) << '\n';
  CHECK(app::replayRecording(out / "resealed.txt").mismatches == 1);
  // Cut anywhere before its end record, the recording is refused, saying what is missing.
  std::ofstream(out / "cut.txt") << text.substr(0, lineEnd - 3);
  CHECK_THROWS_WITH(app::replayRecording(out / "cut.txt"), Catch::Contains("end record"));
}

TEST_CASE("A recording keeps every pose and frame while the main thread is away for 3 s", "[app][replay]") {
  // The render thread drains the pipeline once a frame; a software renderer on a loaded CPU
  // has taken over a second for one (CI), and the recording then lost poses that frames used.
  const RecordedSlide setup(outputDir("app_replay_stall"));
  const auto& [sceneOptions, scene, slide, recording] = setup;
  constexpr int kPoses = 3000;  // 3 s of a 1 kHz input, drained once at the end
  {
    app::TouchPipeline pipeline(scene, {.sceneOptions = sceneOptions, .haptic = {}, .sinks = {.glove = "none", .record = recording.string()},
                                        .drive = app::TouchDrive::Stepped});
    for (int i = 0; i < kPoses; ++i) {
      HandPose pose = slide.poseAt(slide.duration_s() * i / (kPoses - 1));
      pose.t_ns = 1'000'000'000 + std::int64_t(i) * 1'000'000;
      pipeline.publishPose(pose);
      REQUIRE(pipeline.tick(pose.t_ns));
    }
    pipeline.drain();
    CHECK(pipeline.droppedRecords() == 0);
    pipeline.stop();
  }
  const app::ReplayResult r = app::replayRecording(recording);
  CHECK(r.poses == kPoses);
  CHECK(r.frames == kPoses);
  CHECK(r.mismatches == 0);
}

TEST_CASE("Replay rejects malformed recordings naming the file and line", "[app][replay]") {
  const auto out = outputDir("app_replay_errors");
  std::ofstream(out / "bad_magic.txt") << "hello\n";
  CHECK_THROWS_WITH(app::replayRecording(out / "bad_magic.txt"), Catch::Contains("bad_magic.txt: line 1"));
  std::ofstream(out / "bad_record.txt") << app::kRecordingMagic << "\nscene mm_per_pixel=0 builtin=1 gltf=0: dataset=0:\n"
                                        << "config rate_hz=1000 model=paper mapping=five gain=1 pose_timeout_ms=50 sampling=predict latency_ms=0\nX 1\n";
  CHECK_THROWS_WITH(app::replayRecording(out / "bad_record.txt"), Catch::Contains("line 4: unknown record 'X'"));
  std::ofstream(out / "missing_pose.txt") << app::kRecordingMagic << "\nscene mm_per_pixel=0 builtin=1 gltf=0: dataset=0:\n"
                                          << "config rate_hz=1000 model=paper mapping=five gain=1 pose_timeout_ms=50 sampling=predict latency_ms=0\n"
                                          << "F 0 1000 999 999 5 0 0 0 0 0\n";
  CHECK_THROWS_WITH(app::replayRecording(out / "missing_pose.txt"), Catch::Contains("pose t_ns=999 not in the recording"));
  // A client's recording: its frames are the server's, nothing to replay (said by name).
  std::ofstream(out / "client.txt") << app::kRecordingMagic << "\nscene mm_per_pixel=0 builtin=1 gltf=0: dataset=0:\n"
                                    << "config rate_hz=1000 model=paper mapping=five gain=1 pose_timeout_ms=50 sampling=predict latency_ms=0\n"
                                    << "remote server=10.0.0.2:47800\n";
  CHECK_THROWS_WITH(app::replayRecording(out / "client.txt"),
                    Catch::Contains("line 4: a client's recording (its frames came from the server at 10.0.0.2:47800)"));
  CHECK_THROWS_WITH(app::replayRecording(out / "absent.txt"), Catch::Contains("absent.txt': file not found"));
}

TEST_CASE("A recording replays from a stream against the caller's scene", "[app][replay]") {
  // The fuzz target's path: the stream's name in every error, the scene from the caller.
  const app::LoadedScene builtin = app::loadScene({.builtin = true});
  std::vector<app::SceneOptions> asked;
  const app::SceneLoader load = [&](const app::SceneOptions& options) {
    asked.push_back(options);
    return builtin;
  };
  const std::string header = str(app::kRecordingMagic, "\nscene mm_per_pixel=0 builtin=0 gltf=0: dataset=4:ds/x\n",
                                  "config rate_hz=1000 model=paper mapping=five gain=1 pose_timeout_ms=50 sampling=predict latency_ms=0\n");
  const std::string body = header + "F 0 1000 0 1000 5 0 0 0 0 0\n";
  std::stringstream sealed;
  sealed << body << "E 4 " << std::hex << app::recordingChecksum(body) << '\n';
  const app::ReplayResult r = app::replayRecording(sealed, "stream", load);
  CHECK(r.frames == 1);
  CHECK(r.mismatches == 0);
  REQUIRE(asked.size() == 1);
  CHECK(asked[0].dataset == "ds/x");
  std::istringstream cut(body);
  CHECK_THROWS_WITH(app::replayRecording(cut, "stream", load),
                    Catch::Contains("stream: ends after line 4 without its end record (E)") && Catch::Contains("(1 frames read)"));
  std::istringstream frameFirst(str(app::kRecordingMagic, "\nscene mm_per_pixel=0 builtin=1 gltf=0: dataset=0:\nF 0 1 0 1 0\n"));
  CHECK_THROWS_WITH(app::replayRecording(frameFirst, "stream", load), Catch::Contains("stream: line 3: actuator frame before the config line"));
  // Times the loop subtracts and offsets stay within the stamp budget (2^63-1 overflowed it).
  std::istringstream farTick(header + "F 0 9223372036854775807 0 -9223372036854775808 5 0 0 0 0 0\n");
  CHECK_THROWS_WITH(app::replayRecording(farTick, "stream", load),
                    Catch::Contains("stream: line 4: frame t_ns 9223372036854775807 is beyond +-2^61 ns"));
  std::istringstream farHand(header + "F 0 0 0 -2305843009213693953 5 0 0 0 0 0\n");
  CHECK_THROWS_WITH(app::replayRecording(farHand, "stream", load), Catch::Contains("stream: line 4: frame hand_t_ns"));
  std::istringstream farPose(header + "P 2305843009213693953 0 1\n");
  CHECK_THROWS_WITH(app::replayRecording(farPose, "stream", load), Catch::Contains("stream: line 4: pose t_ns"));
}

TEST_CASE("Scene options round-trip through a recording header", "[app][replay]") {
  app::SceneOptions options;
  options.dataset = "/data/with space/p2t";
  options.mmPerPixel = 0.25;
  const app::SceneOptions back = app::decodeSceneOptions(app::encodeSceneOptions(options), "test");
  CHECK(back.dataset == options.dataset);
  CHECK(back.gltf.empty());
  CHECK(back.mmPerPixel == 0.25);
  CHECK_FALSE(back.builtin);
  app::HapticOptions haptic;
  haptic.gain = 0.7f;
  haptic.preset = app::MappingPreset::VTouching;
  const app::HapticOptions h = app::decodeHapticOptions(app::encodeHapticOptions(haptic), "test");
  CHECK(h.gain == 0.7f);
  CHECK(h.preset == app::MappingPreset::VTouching);
  // A recording's pose timeout is checked before it becomes integer nanoseconds (1e30 did not
  // fit: an undefined conversion), with the recording named.
  for (const char* timeout : {"1e30", "-1", "10001"}) {
    const std::string line = std::string("rate_hz=1000 model=paper mapping=five gain=1 pose_timeout_ms=") + timeout +
                             " sampling=predict latency_ms=0";
    CHECK_THROWS_WITH(app::decodeHapticOptions(line, "r.rec"), Catch::Contains("r.rec") && Catch::Contains("pose_timeout_ms"));
  }
}

TEST_CASE("Bad scene files give one error naming the file", "[app][scene]") {
  app::SceneOptions options;
  options.gltf = "/nonexistent/scene.gltf";
  CHECK_THROWS_WITH(app::loadScene(options), Catch::Contains("/nonexistent/scene.gltf"));
  options = {};
  options.dataset = "/nonexistent/dataset";
  CHECK_THROWS_WITH(app::loadScene(options), Catch::Contains("/nonexistent/dataset"));
}

TEST_CASE("Dataset objects with per-taxel waveforms get them in their haptic map", "[app][dataset]") {
  const auto out = outputDir("app_waveforms");
  const auto dataset = writeBandDataset(out / "dataset", "band", 64, 32, 0.5f, 0.75f, 0.5);
  const auto dir = dataset / "band/waveforms";
  std::filesystem::create_directories(dir);
  constexpr int kHeight = 4, kWidth = 8, kSamples = 16;
  std::ofstream header(dir / "header.bin", std::ios::binary), data(dir / "data.bin", std::ios::binary);
  auto put32 = [](std::ofstream& f, auto v) { f.write(reinterpret_cast<const char*>(&v), 4); };  // little-endian host
  put32(header, std::int32_t(kHeight));
  put32(header, std::int32_t(kWidth));
  for (int i = 0; i < kHeight * kWidth; ++i) put32(header, std::int32_t(i * kSamples));
  for (int i = 0; i < kHeight * kWidth; ++i) {
    const float amplitude = 0.1f * float(i % kWidth + 1);  // stronger to the right
    for (int s = 0; s < kSamples; ++s) put32(data, 1.0f + amplitude * std::sin(float(s)));
  }
  header.close();
  data.close();
  app::SceneOptions options;
  options.dataset = dataset.string();
  const app::LoadedScene scene = app::loadScene(options);
  const auto& map = scene.haptic->maps->at(0);
  CHECK_FALSE(map.waveforms().empty());
  CHECK(map.width() == kWidth);
  CHECK(map.sample({0.95f, 0.5f}, false) > map.sample({0.05f, 0.5f}, false));

  std::ofstream(dir / "header.bin", std::ios::binary) << "x";  // truncated
  CHECK_THROWS_WITH(app::loadScene(options), Catch::Contains("header.bin"));
}
