#include "modes/trajectory_run.hpp"

#include <climits>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <tuple>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "modes/hand_control.hpp"
#include "modes/touch_session.hpp"
#include "ui/touch_figure.hpp"
#include "vt/core/budgets.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
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

namespace {

// The contact samples the figures are drawn from, at most budget::kFigureSamplesPerFinger per
// finger: when a finger's series is full every other sample is dropped and from then on only every
// 2nd (4th, ...) tick is kept. Memory stays flat however long the run; traces.csv keeps every tick.
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

TrajectoryRunResult runTrajectory(const TrajectoryRunOptions& options) {
  const Trajectory trajectory = loadTrajectory(options.trajectory);
  if (!(options.fps >= 0.0 && options.fps <= 1000.0)) fail("render: --fps ", options.fps, " out of range 0..1000");
  if (options.every < 1) fail("render: --every ", options.every, " must be at least 1");
  std::error_code ec;
  fs::create_directories(options.outDir, ec);
  if (ec) fail(options.outDir.string(), ": cannot create the output folder: ", ec.message());

  const LoadedScene scene = loadScene(options.scene);
  log::info("trajectory ", options.trajectory.string(), " (", trajectory.duration_s(), " s) over ", scene.description);
  ManualClock clock;
  TouchSession session(scene, {.sceneOptions = options.scene, .haptic = options.haptic, .sinks = options.sinks,
                               .drive = TouchDrive::Stepped, .clock = &clock});
  const haptics::HapticConfig& config = session.config();

  std::shared_ptr<renderer::Device> device;
  std::unique_ptr<renderer::Renderer> gpu;
  std::unique_ptr<renderer::OffscreenTarget> target;
  if (options.fps > 0.0) {
    device = renderer::Device::create({.validate = options.validate});
    log::info("device: ", device->description());
    gpu = std::make_unique<renderer::Renderer>(device);
    gpu->setScene(scene.scene);
    target = std::make_unique<renderer::OffscreenTarget>(device, std::uint32_t(options.width), std::uint32_t(options.height));
  }

  TrajectoryRunResult result;
  result.tracesCsv = options.outDir / "traces.csv";
  // Streamed to disk as the run goes (every write checked: a full disk stops the run at once) and
  // renamed into place at the end, so a failed run leaves the previous traces.csv, not half of one.
  OutputFile csv(result.tracesCsv);
  csv.write("time_s,finger,contact,material,u,v,depth_m,map_value,intensity,across_weight\n");
  FigureTraces traces(config.contacts.size());
  std::map<int, std::size_t> touchesPerObject;

  const double t0 = trajectory.keys.front().t_s;
  const auto period_ns = std::int64_t(std::llround(1e9 / double(config.rate_hz)));
  const auto duration_ns = std::int64_t(std::llround(trajectory.duration_s() * 1e9));
  const std::int64_t framePeriod_ns = options.fps > 0.0 ? std::int64_t(std::llround(1e9 / options.fps)) : 0;
  std::int64_t nextFrame_ns = 0;
  int frameIndex = 0;
  session.onTrace([&](const haptics::ContactTrace& t) {
    const Scene& s = *scene.scene;
    const std::string material = t.inContact && t.material >= 0 ? s.materials[std::size_t(t.material)].name : "";
    char line[256];
    const int length = std::snprintf(line, sizeof line, "%.4f,%s,%d,%s,%.5f,%.5f,%.5f,%.5f,%.5f,%.3f\n",
                                     double(t.t_ns) * 1e-9, fingerName(fingerOfTip(config.contacts[t.contact].joint)),
                                     int(t.inContact), material.c_str(), double(t.u), double(t.v), double(t.depth_m),
                                     double(t.mapValue), double(t.intensity), double(t.acrossWeight));
    csv.write(line, std::min(std::size_t(std::max(length, 0)), sizeof line - 1));
    if (t.inContact) ++touchesPerObject[int(t.object)];
    result.peakIntensity = std::max(result.peakIntensity, t.intensity);
    traces.add(t);
  });
  const Clock& wall = SteadyClock::instance();
  const std::int64_t start_ns = wall.now_ns();
  std::int64_t nextReport_ns = start_ns + 1'000'000'000;
  for (std::int64_t t_ns = 0; t_ns <= duration_ns; t_ns += period_ns) {
    if (stopRequested()) {
      // Ctrl-C ends a long run like every mode: what was computed so far is written whole.
      log::warn("trajectory: stopped at ", double(t_ns) * 1e-9, " s of ", double(duration_ns) * 1e-9, " s");
      result.stoppedEarly = true;
      break;
    }
    if (options.progress && wall.now_ns() >= nextReport_ns) {
      reportProgress(result.framesWritten, double(t_ns) / double(std::max<std::int64_t>(1, duration_ns)),
                     double(wall.now_ns() - start_ns) * 1e-9);
      nextReport_ns += 1'000'000'000;
    }
    // Scripted input: one exact pose per tick, stamped with the time it describes.
    HandPose pose = trajectory.poseAt(t0 + double(t_ns) * 1e-9);
    pose.t_ns = t_ns;
    pose.sequence = result.ticks;
    session.publishPose(pose);
    clock.set(t_ns);
    session.tick(t_ns);
    ++result.ticks;
    session.drain();
    if (gpu && t_ns >= nextFrame_ns) {
      nextFrame_ns += framePeriod_ns;
      renderer::FrameDesc frame;
      frame.views = {scene.scene->camera.view(float(options.width) / float(options.height))};
      frame.overlay = options.overlay;
      renderer::appendHandPrimitives(visualProxy(pose, *scene.haptic->collision), renderer::kHandColor, frame.hand);
      if (frameIndex % options.every == 0) {
        gpu->render(*target, frame);
        char name[32];
        std::snprintf(name, sizeof name, "frame_%05d.png", frameIndex / options.every);
        savePng(options.outDir / name, target->readback());
        ++result.framesWritten;
      }
      ++frameIndex;
    }
  }
  if (options.progress && isatty(STDERR_FILENO) && wall.now_ns() > start_ns + 1'000'000'000) std::fputc('\n', stderr);
  session.stop();  // finishes --record/--record-csv/--record-wav like every mode
  csv.commit();
  // What the traces were measured on, beside them: the scene and how its intensities compare.
  writeFileAtomically(options.outDir / "traces.json",
                      nlohmann::json{{"scene", scene.description}, {"intensity", scene.scene->intensity},
                                     {"trajectory", options.trajectory.string()}}.dump(1) + "\n");

  // One figure per touched object that has a vibration map (not the table), and figure.png for
  // the one touched most.
  int most = -1;
  std::size_t mostTouches = 0;
  std::set<std::string> figures;
  for (const auto& [object, touches] : touchesPerObject) {
    const SceneObject& o = scene.scene->objects[std::size_t(object)];
    if (scene.scene->materials[std::size_t(o.material)].vibrationMap < 0) continue;
    const std::string name = "figure_" + o.name + ".png";
    writeFigure(*scene.scene, object, traces.series(), config, options.outDir / name);
    figures.insert(name);
    if (touches > mostTouches) most = object, mostTouches = touches;
  }
  if (most < 0) {
    log::warn("trajectory: the hand touched no tactile object; figure.png shows the first one");
    most = 0;
    for (std::size_t o = 0; o < scene.scene->objects.size(); ++o) {
      if (scene.scene->materials[std::size_t(scene.scene->objects[o].material)].vibrationMap >= 0) {
        most = int(o);
        break;
      }
    }
  }
  result.figurePng = options.outDir / "figure.png";
  writeFigure(*scene.scene, most, traces.series(), config, result.figurePng);
  removeStaleOutputs(options.outDir, result.framesWritten, figures);
  if (gpu) {
    gpu->waitIdle();
    result.validationMessages = device->validationMessageCount();
  }
  return result;
}

int trajectoryCommand(cli::Args& args, const std::string& trajectory) {
  TrajectoryRunOptions options;
  options.trajectory = trajectory;
  const auto out = args.value("out");
  std::tie(options.width, options.height) = args.sizeOr("size", {options.width, options.height});
  options.fps = args.doubleOr("fps", options.fps);
  options.every = args.intOr("every", options.every);
  options.validate = args.flag("validate");
  options.overlay = args.flag("overlay");
  const bool quiet = args.flag("quiet");
  options.progress = !quiet;
  if (quiet && log::level() < log::Level::Warn) log::setLevel(log::Level::Warn);
  options.scene = readSceneOptions(args);
  options.haptic = readHapticOptions(args);
  options.sinks = readHapticSinks(args, "none");
  args.finish();
  if (!out) fail("render: --out DIR is required");
  options.outDir = *out;
  const TrajectoryRunResult r = runTrajectory(options);
  if (!quiet) std::printf("%s %llu haptic ticks; wrote %d frames, %s, %s (peak intensity %.3f)\n",
              r.stoppedEarly ? "stopped (Ctrl-C) after" : "ran", static_cast<unsigned long long>(r.ticks),
              r.framesWritten, r.tracesCsv.c_str(), r.figurePng.c_str(),
              double(r.peakIntensity));
  if (options.validate) {
    std::printf("validation messages: %llu\n", static_cast<unsigned long long>(r.validationMessages));
    if (r.validationMessages > 0) return 3;
  }
  return 0;
}

}  // namespace vt::app
