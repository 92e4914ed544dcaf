// `vtouching render`: a scene (the same options as run) drawn offscreen with the Vulkan renderer,
// written as PNGs.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <vector>

#include "cli.hpp"
#include "modes/frame_stats.hpp"
#include "modes/hand_view.hpp"
#include "modes/scene_source.hpp"
#include "modes/trajectory_run.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/renderer/demo_frame.hpp"
#include "vt/renderer/device.hpp"
#include "vt/renderer/offscreen_target.hpp"
#include "vt/renderer/renderer.hpp"

VT_COMMAND(render) {
  // A scripted hand path is the app's offscreen run (frames + traces + Fig. 5), in app/modes.
  if (const auto trajectory = args.value("trajectory")) return vt::app::trajectoryCommand(args, *trajectory);
  const auto outDir = args.value("out");
  const auto [width, height] = args.sizeOr("size", {1280, 720});
  const int frames = args.intOr("frames", 10);
  const bool stereo = args.flag("stereo");
  const bool overlay = args.flag("overlay");
  const bool validate = args.flag("validate");
  const auto texture = args.value("texture");
  const bool quiet = args.flag("quiet");  // only errors (and the validation count with --validate)
  if (quiet && vt::log::level() < vt::log::Level::Warn) vt::log::setLevel(vt::log::Level::Warn);
  const vt::app::SceneOptions sceneOptions = vt::app::readSceneOptions(args);
  const vt::app::HandViewOptions hand = vt::app::readHandViewOptions(args);
  args.finish();
  if (!outDir) vt::fail("render: --out DIR is required");
  if (frames < 1 || frames > 100000) vt::fail("render: --frames ", frames, " out of range 1..100000");

  vt::Scene scene = *vt::app::loadScene(sceneOptions).scene;
  if (texture) {  // replaces the photo of the first object that has one and a vibration map (a plate)
    const auto plate = std::find_if(scene.materials.begin(), scene.materials.end(),
                                    [](const vt::Material& m) { return m.vibrationMap >= 0 && m.albedoTexture >= 0; });
    if (plate == scene.materials.end()) vt::fail("render: --texture: the scene has no textured plate");
    scene.textures.at(std::size_t(plate->albedoTexture)) = vt::loadImage8(*texture, 4);
  }
  std::error_code ec;
  std::filesystem::create_directories(*outDir, ec);
  if (ec) vt::fail("render: cannot create output folder '", *outDir, "': ", ec.message());

  auto device = vt::renderer::Device::create({.validate = validate});
  if (!quiet) std::printf("device: %s%s\n", device->description().c_str(), validate ? " (validation on)" : "");
  vt::renderer::Renderer renderer(device);
  if (stereo && !quiet) {
    std::printf("stereo: %s\n", renderer.usesMultiview() ? "multiview (both eyes in one pass)"
                                                         : "one pass per eye (this driver's multiview is unreliable)");
  }
  renderer.setScene(std::make_shared<const vt::Scene>(scene));
  vt::app::applyHandView(renderer, hand);
  const std::uint32_t layers = stereo ? 2 : 1;
  vt::renderer::OffscreenTarget target(device, std::uint32_t(width), std::uint32_t(height), layers);
  const vt::renderer::FrameDesc frame =
      vt::renderer::makeDemoFrame(scene, std::uint32_t(width), std::uint32_t(height), stereo, overlay, hand.style);

  // With two frames in flight each render() call waits for the frame two back, so in steady state
  // its duration is the frame time. The first two calls (pipeline creation, nothing to wait for
  // yet) are warm-up and reported apart.
  constexpr int kWarmupFrames = 2;
  const vt::Clock& clock = vt::SteadyClock::instance();
  std::vector<double> times_ms;
  double warmup_ms = 0.0;
  for (int i = 0; i < frames; ++i) {
    const std::int64_t t0 = clock.now_ns();
    renderer.render(target, frame);
    const double ms = double(clock.now_ns() - t0) * 1e-6;
    if (i < kWarmupFrames) {
      warmup_ms += ms;
    } else {
      times_ms.push_back(ms);
    }
  }
  const std::vector<std::string> names = stereo ? std::vector<std::string>{"left.png", "right.png"}
                                                : std::vector<std::string>{"frame.png"};
  for (std::uint32_t layer = 0; layer < layers; ++layer) {
    const std::filesystem::path path = std::filesystem::path(*outDir) / names[layer];
    vt::savePng(path, target.readback(layer));
    if (!quiet) std::printf("wrote %s\n", path.c_str());
  }
  const vt::app::FrameStats stats = vt::app::summarizeFrameTimes(times_ms);
  if (!quiet && times_ms.empty()) {
    std::printf("frame time: use --frames 3 or more for steady-state figures (warm-up %.1f ms)\n", warmup_ms);
  } else if (!quiet) {
    std::printf("frame time %dx%d%s%s: mean %.2f ms, p95 %.2f ms, p99 %.2f ms over %zu frames (warm-up %.1f ms)\n",
                width, height, stereo ? " stereo" : "", overlay ? " overlay" : "", stats.mean_ms, stats.p95_ms, stats.p99_ms,
                times_ms.size(), warmup_ms);
  }
  if (validate) {
    renderer.waitIdle();
    const std::uint64_t messages = device->validationMessageCount();
    std::printf("validation messages: %llu\n", static_cast<unsigned long long>(messages));
    if (messages > 0) {
      std::fprintf(stderr, "vtouching: error: render: %llu validation messages (see log above)\n",
                   static_cast<unsigned long long>(messages));
      return 3;
    }
  }
  return 0;
}
