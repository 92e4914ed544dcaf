#include "modes/trajectory_run.hpp"

#include <cerrno>
#include <climits>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <optional>
#include <set>
#include <tuple>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "modes/contact_markers.hpp"
#include "modes/hand_control.hpp"
#include "modes/touch_pipeline.hpp"
#include "modes/video_encoder.hpp"
#include "ui/touch_figure.hpp"
#include "vt/core/budgets.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
#include "vt/core/file_io.hpp"
#include "vt/core/log.hpp"
#include "vt/core/output_file.hpp"
#include "vt/core/stop.hpp"
#include "vt/renderer/device.hpp"
#include "vt/renderer/offscreen_target.hpp"
#include "vt/renderer/renderer.hpp"
#include "vt/scene/trajectory.hpp"

namespace vt::app {
namespace fs = std::filesystem;

fs::path defaultTrajectory() {
  const fs::path assets = defaultAssetsDir();
  if (assets.empty() || !fs::exists(assets / "trajectories/slide.csv")) return {};
  return assets / "trajectories/slide.csv";
}

// The contact samples the figures are drawn from, at most budget::kFigureSamplesPerFinger per
// finger: when a finger's series is full every other sample is dropped and from then on only every
// 2nd (4th, ...) tick is kept. Memory stays flat however long the run; traces.csv keeps every tick.
// Outside the anonymous namespace: RunOutputs::State, a member of an exported class, holds one.
class FigureTraces {
 public:
  explicit FigureTraces(std::size_t fingers) : m_series(fingers), m_stride(fingers, 1), m_seen(fingers, 0) {}

  void add(const haptics::ContactTrace& t) {
    const std::size_t c = t.contact;
    if (m_seen[c]++ % m_stride[c] != 0) return;
    std::vector<haptics::ContactTrace>& series = m_series[c];
    if (series.size() >= budget::kFigureSamplesPerFinger) {
      for (std::size_t i = 0; 2 * i < series.size(); ++i) series[i] = series[2 * i];
      series.resize((series.size() + 1) / 2);
      m_stride[c] *= 2;
    }
    series.push_back(t);
  }
  const std::vector<std::vector<haptics::ContactTrace>>& series() const { return m_series; }

 private:
  std::vector<std::vector<haptics::ContactTrace>> m_series;
  std::vector<std::uint64_t> m_stride, m_seen;
};

namespace {

// The figure for one object, limited to the time any finger spent on it (plus a margin): each
// finger's intensity while it touched this object or nothing (a gap while on another object),
// its path where it touched the object's top face. Contacts on the side faces (the plate's
// edges, with their own UVs) are not drawn on the photo but counted in the figure's note.
void writeFigure(const Scene& scene, int object, const std::vector<std::vector<haptics::ContactTrace>>& traces,
                 const haptics::HapticConfig& config, const fs::path& png) {
  const SceneObject& target = scene.objects[std::size_t(object)];
  const Material& material = scene.materials[std::size_t(target.material)];
  constexpr std::int64_t kMargin_ns = 200'000'000;
  std::int64_t first_ns = INT64_MAX, last_ns = INT64_MIN;
  for (const auto& finger : traces) {
    for (const auto& t : finger) {
      if (t.inContact && int(t.object) == object) first_ns = std::min(first_ns, t.t_ns), last_ns = std::max(last_ns, t.t_ns);
    }
  }
  const glm::vec3 up = glm::normalize(glm::mat3(target.T_world_object) * glm::vec3(0.0f, 1.0f, 0.0f));
  const double tick_s = 1.0 / double(config.rate_hz);
  double side_s = 0.0;
  std::vector<ui::FingerSeries> series;
  for (std::size_t c = 0; c < traces.size(); ++c) {
    ui::FingerSeries s;
    s.name = fingerName(fingerOfTip(config.contacts[c].joint));
    s.color = ui::fingerColor(fingerOfTip(config.contacts[c].joint));
    std::int64_t previous_ns = -1;
    for (const auto& t : traces[c]) {
      if (first_ns <= last_ns && (t.t_ns < first_ns - kMargin_ns || t.t_ns > last_ns + kMargin_ns)) continue;
      const bool here = t.inContact && int(t.object) == object;
      const bool side = here && glm::dot(t.normal, up) < 0.7f;
      // Long runs keep every 2nd, 4th... tick (FigureTraces): a sample stands for the time since the last.
      side_s += side ? (previous_ns < 0 ? tick_s : double(t.t_ns - previous_ns) * 1e-9) : 0.0;
      previous_ns = t.t_ns;
      s.t_s.push_back(double(t.t_ns) * 1e-9);
      s.intensity.push_back(t.inContact && !here ? std::nanf("") : t.intensity);
      s.uv.push_back({t.u, t.v});
      s.onPath.push_back(here && !side);
    }
    series.push_back(std::move(s));
  }
  Image8 texture = material.albedoTexture >= 0 ? scene.textures[std::size_t(material.albedoTexture)] : Image8(64, 64, 4);
  if (material.albedoTexture < 0) std::fill(texture.pixels.begin(), texture.pixels.end(), std::uint8_t(200));
  ui::TouchFigureInfo info;
  info.title = "touch path over " + material.name;
  info.photoWidth_m = material.physicalWidth_m;
  if (side_s > 0.0) {
    char note[96];
    std::snprintf(note, sizeof note, "side faces (plate edges) touched for %.2f s in all: not drawn", side_s);
    info.note = note;
  }
  savePng(png, ui::makeTouchFigure(texture, series, info));
  fs::path svg = png;
  svg.replace_extension(".svg");
  writeFileAtomically(svg, ui::makeTouchFigureSvg(texture, series, info));
}

// One line on stderr: frames written, their rate, the share of trajectory time done and the
// time left at the rate so far (rewritten in place on a terminal).
void reportProgress(int frames, double done, double elapsed_s) {
  const double left_s = done > 0.0 ? elapsed_s * (1.0 - done) / done : 0.0;
  std::fprintf(stderr, "%srender: %d frames (%.1f fps), %3.0f %% of the trajectory, %.0f s left%s", isatty(STDERR_FILENO) ? "\r" : "",
               frames, elapsed_s > 0.0 ? double(frames) / elapsed_s : 0.0, done * 100.0, left_s,
               isatty(STDERR_FILENO) ? "" : "\n");
  std::fflush(stderr);
}

// A run into a folder that holds an earlier run's outputs replaces them; frames and figures (PNG,
// SVG) this
// run did not write (a longer earlier run, another scene) go too, so the folder shows one run.
void removeStaleOutputs(const fs::path& dir, int framesWritten, const std::set<std::string>& figures) {
  std::error_code ec;
  int removed = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    const fs::path extension = entry.path().extension();
    if (extension != ".png" && extension != ".svg") continue;
    int index = -1;
    const bool staleFrame = std::sscanf(name.c_str(), "frame_%5d.png", &index) == 1 && name.size() == 15 &&
                            index >= framesWritten;
    // A figure's .svg goes with its .png.
    const bool staleFigure = name.rfind("figure_", 0) == 0 &&
                             !figures.count(entry.path().stem().string() + ".png");
    if ((staleFrame || staleFigure) && fs::remove(entry.path(), ec)) ++removed;
  }
  if (removed > 0) log::info("trajectory: removed ", removed, " frames and figures of an earlier run from ", dir.string());
}

}  // namespace

struct RunOutputs::State {
  State(const LoadedScene& s, const haptics::HapticConfig& c, const RunOutputOptions& o)
      : scene(s), config(c), options(o), csv(o.outDir / "traces.csv"), traces(c.contacts.size()),
        latest(c.contacts.size()) {}
  LoadedScene scene;  // shared: the run may outlive the caller's copy (a replay)
  haptics::HapticConfig config;
  RunOutputOptions options;
  std::shared_ptr<renderer::Device> device;
  std::unique_ptr<renderer::Renderer> gpu;
  std::unique_ptr<renderer::OffscreenTarget> target;
  std::unique_ptr<VideoEncoder> video;
  // Streamed to disk as the run goes (every write checked: a full disk stops the run at once) and
  // renamed into place at the end, so a failed run leaves the previous traces.csv, not half of one.
  OutputFile csv;
  FigureTraces traces;
  std::vector<haptics::ContactTrace> latest;  // the newest trace of each contact point (the frame's rings)
  std::map<int, std::size_t> touchesPerObject;
  std::int64_t framePeriod_ns = 0, nextFrame_ns = 0;
  int frameIndex = 0, framesWritten = 0;
  float peakIntensity = 0.0f;
  std::int64_t start_ns = 0, nextReport_ns = 0;
};

RunOutputs::RunOutputs(const LoadedScene& scene, const haptics::HapticConfig& config, const RunOutputOptions& options) {
  if (!(options.fps >= 0.0 && options.fps <= 1000.0)) fail(options.command, ": --fps ", options.fps, " out of range 0..1000");
  if (options.every < 1) fail(options.command, ": --every ", options.every, " must be at least 1");
  std::error_code ec;
  if (fs::exists(options.outDir, ec) && !fs::is_directory(options.outDir, ec))
    fail(options.command, ": output folder '", options.outDir.string(), "' is a file; give a folder (it is made when missing)");
  fs::create_directories(options.outDir, ec);
  if (ec) fail(options.command, ": ", describeErrno(options.outDir, "create the output folder", ec.value()));
  m_state = std::make_unique<State>(scene, config, options);
  State& s = *m_state;
  s.csv.write("time_s,finger,contact,material,u,v,depth_m,map_value,intensity,across_weight\n");
  if (options.fps > 0.0) {
    s.device = renderer::Device::create({.validate = options.validate});
    log::info("device: ", s.device->description());
    s.gpu = std::make_unique<renderer::Renderer>(s.device);
    s.gpu->setScene(scene.scene);
    applyHandView(*s.gpu, options.hand);
    s.target = std::make_unique<renderer::OffscreenTarget>(s.device, std::uint32_t(options.width), std::uint32_t(options.height));
    s.framePeriod_ns = std::int64_t(std::llround(1e9 / options.fps));
    if (!options.video.empty())
      s.video = std::make_unique<VideoEncoder>(options.video, options.width, options.height, options.fps / options.every,
                                               options.command);
  }
  s.start_ns = SteadyClock::instance().now_ns();
  s.nextReport_ns = s.start_ns + 1'000'000'000;
}

RunOutputs::~RunOutputs() = default;

void RunOutputs::trace(const haptics::ContactTrace& t) {
  State& s = *m_state;
  const Scene& scene = *s.scene.scene;
  const std::string material = t.inContact && t.material >= 0 ? scene.materials[std::size_t(t.material)].name : "";
  char line[256];
  const int length = std::snprintf(line, sizeof line, "%.4f,%s,%d,%s,%.5f,%.5f,%.5f,%.5f,%.5f,%.3f\n",
                                   double(t.t_ns) * 1e-9, fingerName(fingerOfTip(s.config.contacts[t.contact].joint)),
                                   int(t.inContact), material.c_str(), double(t.u), double(t.v), double(t.depth_m),
                                   double(t.mapValue), double(t.intensity), double(t.acrossWeight));
  s.csv.write(line, std::min(std::size_t(std::max(length, 0)), sizeof line - 1));
  if (t.inContact) ++s.touchesPerObject[int(t.object)];
  s.peakIntensity = std::max(s.peakIntensity, t.intensity);
  s.traces.add(t);
  if (t.contact < s.latest.size()) s.latest[t.contact] = t;
}

void RunOutputs::tick(std::int64_t t_ns, const HandPose& pose, double done) {
  State& s = *m_state;
  const RunOutputOptions& options = s.options;
  const Clock& wall = SteadyClock::instance();
  if (options.progress && wall.now_ns() >= s.nextReport_ns) {
    reportProgress(s.framesWritten, done, double(wall.now_ns() - s.start_ns) * 1e-9);
    s.nextReport_ns = wall.now_ns() + 1'000'000'000;  // after a slow frame: one line, not a burst
  }
  if (!s.gpu || t_ns < s.nextFrame_ns) return;
  s.nextFrame_ns += s.framePeriod_ns;
  if (s.frameIndex++ % options.every != 0) return;
  renderer::FrameDesc frame;
  frame.views = {s.scene.scene->camera.view(float(options.width) / float(options.height))};
  frame.overlay = options.overlay;
  const HandPose drawn = visualProxy(pose, *s.scene.haptic->collision);
  renderer::appendHand(drawn, options.hand.style, frame);
  appendContactMarkers(s.latest, s.config, drawn, *s.scene.haptic->collision, frame.contacts);
  s.gpu->render(*s.target, frame);
  if (s.video) {
    s.video->write(s.target->readback());
  } else {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d.png", s.framesWritten);
    savePng(options.outDir / name, s.target->readback());
  }
  ++s.framesWritten;
}

void RunOutputs::finish(const std::string& sourceKind, const std::string& source, TrajectoryRunResult& result) {
  State& s = *m_state;
  const RunOutputOptions& options = s.options;
  const LoadedScene& scene = s.scene;
  if (options.progress && isatty(STDERR_FILENO) && SteadyClock::instance().now_ns() > s.start_ns + 1'000'000'000)
    std::fputc('\n', stderr);
  // The video first: when ffmpeg fails (or the stop request cut it short) no output is committed.
  if (s.video) s.video->finish();
  s.csv.commit();
  result.tracesCsv = options.outDir / "traces.csv";
  result.framesWritten = s.framesWritten;
  result.peakIntensity = s.peakIntensity;
  // What the traces were measured on, beside them: the scene and how its intensities compare.
  writeFileAtomically(options.outDir / "traces.json",
                      nlohmann::json{{"scene", scene.description}, {"intensity", scene.scene->intensity},
                                     {sourceKind, source}}.dump(1) + "\n");

  // One figure per touched object that has a vibration map (not the table), and figure.png for
  // the one touched most.
  int most = -1;
  std::size_t mostTouches = 0;
  std::set<std::string> figures;
  for (const auto& [object, touches] : s.touchesPerObject) {
    const SceneObject& o = scene.scene->objects[std::size_t(object)];
    if (scene.scene->materials[std::size_t(o.material)].vibrationMap < 0) continue;
    const std::string name = "figure_" + o.name + ".png";
    writeFigure(*scene.scene, object, s.traces.series(), s.config, options.outDir / name);
    figures.insert(name);
    if (touches > mostTouches) most = object, mostTouches = touches;
  }
  if (most < 0) {
    log::warn("run: the hand touched no tactile object; figure.png shows the first one");
    most = 0;
    for (std::size_t o = 0; o < scene.scene->objects.size(); ++o) {
      if (scene.scene->materials[std::size_t(scene.scene->objects[o].material)].vibrationMap >= 0) {
        most = int(o);
        break;
      }
    }
  }
  result.figurePng = options.outDir / "figure.png";
  writeFigure(*scene.scene, most, s.traces.series(), s.config, result.figurePng);
  removeStaleOutputs(options.outDir, s.video ? 0 : s.framesWritten, figures);
  if (s.gpu) {
    s.gpu->waitIdle();
    result.validationMessages = s.device->validationMessageCount();
  }
}

void refuseSharedRunOutputs(const RunOutputOptions& options, const HapticSinks* sinks, const fs::path& extra) {
  const fs::path& out = options.outDir;
  std::vector<NamedOutput> outputs{{"--video", options.video}};
  if (!out.empty()) {
    outputs.insert(outputs.end(), {{"--out (its traces.csv)", out / "traces.csv"},
                                   {"--out (its traces.json)", out / "traces.json"},
                                   {"--out (its figure.png)", out / "figure.png"}});
    if (!extra.empty()) outputs.push_back({"--out (its " + extra.filename().string() + ")", extra});
  }
  if (sinks) {
    outputs.insert(outputs.end(), {{"--record", sinks->record}, {"--record-csv", sinks->actuatorCsv},
                                   {"--record-wav", sinks->actuatorWav}});
  }
  refuseSharedOutputs(outputs);
}

RunOutputOptions readRunOutputOptions(cli::Args& args, const char* command, bool& quiet) {
  RunOutputOptions options;
  const auto out = args.value("out");
  std::tie(options.width, options.height) = args.sizeOr("size", {options.width, options.height});
  options.fps = args.doubleOr("fps", options.fps);
  options.every = args.intOr("every", options.every);
  options.validate = args.flag("validate");
  options.overlay = args.flag("overlay");
  options.hand = readHandViewOptions(args);
  const auto video = args.value("video");
  quiet = args.flag("quiet");
  options.progress = !quiet;
  if (quiet && log::level() < log::Level::Warn) log::setLevel(log::Level::Warn);
  options.outDir = out.value_or("");
  options.command = command;
  if (video) {
    if (!out) fail(command, ": --video needs --out DIR (for the traces and figures)");
    if (findFfmpeg().empty()) fail(command, ": --video needs the ffmpeg program, which is not installed (Debian package ffmpeg)");
    if (options.width % 2 != 0 || options.height % 2 != 0)
      fail(command, ": --video needs an even width and height (--size ", options.width, "x", options.height, ")");
    if (!(options.fps > 0.0)) fail(command, ": --video needs frames (--fps above 0)");
    options.video = *video;
  }
  return options;
}

TrajectoryRunResult runTrajectory(const TrajectoryRunOptions& options) {
  refuseSharedRunOutputs(options, &options.sinks);
  const Trajectory trajectory = loadTrajectory(options.trajectory);
  const LoadedScene scene = loadScene(options.scene);
  log::info("trajectory ", options.trajectory.string(), " (", trajectory.duration_s(), " s) over ", scene.description);
  ManualClock clock;
  // The outputs outlive the pipeline whose trace listener writes to them: an error that unwinds
  // this function destroys the pipeline (which drains its rings) first.
  std::optional<RunOutputs> outputs;
  TouchPipeline pipeline(scene, {.sceneOptions = options.scene, .haptic = options.haptic, .sinks = options.sinks,
                               .drive = TouchDrive::Stepped, .clock = &clock});
  RunOutputs& out = outputs.emplace(scene, pipeline.config(), options);
  pipeline.onTrace([&out](const haptics::ContactTrace& t) { out.trace(t); });

  TrajectoryRunResult result;
  const double t0 = trajectory.keys.front().t_s;
  const auto period_ns = std::int64_t(std::llround(1e9 / double(pipeline.config().rate_hz)));
  const auto duration_ns = std::int64_t(std::llround(trajectory.duration_s() * 1e9));
  for (std::int64_t t_ns = 0; t_ns <= duration_ns; t_ns += period_ns) {
    if (stopRequested()) {
      // Ctrl-C ends a long run like every mode: what was computed so far is written whole.
      log::warn("trajectory: stopped at ", double(t_ns) * 1e-9, " s of ", double(duration_ns) * 1e-9, " s");
      result.stoppedEarly = true;
      break;
    }
    // Scripted input: one exact pose per tick, stamped with the time it describes.
    HandPose pose = trajectory.poseAt(t0 + double(t_ns) * 1e-9);
    pose.t_ns = t_ns;
    pose.sequence = result.ticks;
    pipeline.publishPose(pose);
    clock.set(t_ns);
    pipeline.tick(t_ns);
    ++result.ticks;
    pipeline.drain();
    out.tick(t_ns, pose, double(t_ns) / double(std::max<std::int64_t>(1, duration_ns)));
  }
  pipeline.stop();  // finishes --record/--record-csv/--record-wav like every mode
  out.finish("trajectory", options.trajectory.string(), result);
  return result;
}

int trajectoryCommand(cli::Args& args, const std::string& trajectory) {
  bool quiet = false;
  TrajectoryRunOptions options;
  static_cast<RunOutputOptions&>(options) = readRunOutputOptions(args, "render", quiet);
  options.trajectory = trajectory;
  options.scene = readSceneOptions(args);
  options.haptic = readHapticOptions(args);
  options.sinks = readHapticSinks(args, "none");
  args.finish();
  if (options.outDir.empty()) fail("render: --out DIR is required");
  const TrajectoryRunResult r = runTrajectory(options);
  if (!quiet) std::printf("%s %llu haptic ticks; wrote %d frames%s%s, %s, %s (peak intensity %.3f)\n",
              r.stoppedEarly ? "stopped (Ctrl-C) after" : "ran", static_cast<unsigned long long>(r.ticks),
              r.framesWritten, options.video.empty() ? "" : " into ", options.video.c_str(), r.tracesCsv.c_str(),
              r.figurePng.c_str(), double(r.peakIntensity));
  if (options.validate) {
    std::printf("validation messages: %llu\n", static_cast<unsigned long long>(r.validationMessages));
    if (r.validationMessages > 0) return 3;
  }
  return 0;
}

}  // namespace vt::app
