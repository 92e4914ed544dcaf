// The desktop preview in a real window (GLFW + Vulkan swapchain + Dear ImGui) with scripted input.
// Needs a display: ctest runs it under xvfb-run (app.desktop_golden_under_xvfb); skips without one.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "app_test_helpers.hpp"
#include "modes/desktop_mode.hpp"
#include "test_support.hpp"
#include "vt/core/error.hpp"
#include "vt/scene/image.hpp"

using namespace vt;

namespace {

struct Difference {
  double psnr_db = 0.0;
  double badFraction = 0.0;  // pixels with a channel off by more than 40
};

Difference compare(const Image8& a, const Image8& b) {
  REQUIRE(a.width == b.width);
  REQUIRE(a.height == b.height);
  double squared = 0.0;
  std::size_t bad = 0;
  const std::size_t pixels = std::size_t(a.width) * std::size_t(a.height);
  for (std::size_t p = 0; p < pixels; ++p) {
    bool off = false;
    for (int c = 0; c < 3; ++c) {
      const int d = int(a.pixels[p * std::size_t(a.channels) + std::size_t(c)]) -
                    int(b.pixels[p * std::size_t(b.channels) + std::size_t(c)]);
      squared += double(d * d);
      off |= std::abs(d) > 40;
    }
    bad += off;
  }
  const double mse = squared / double(pixels * 3);
  return {mse == 0.0 ? 99.0 : 10.0 * std::log10(255.0 * 255.0 / mse), double(bad) / double(pixels)};
}

}  // namespace

TEST_CASE("Desktop preview in a window matches its golden screenshot", "[.desktop]") {
  if (!app::haveDisplay()) VT_SKIP("no display (ctest runs this under xvfb-run)");
  const auto out = test::outputDir("app_desktop");
  app::DesktopOptions options;
  options.frames = 12;
  options.scripted = true;
  options.validate = true;
  options.screenshot = (out / "desktop.png").string();
  options.sinks.record = (out / "desktop.rec").string();
  REQUIRE(app::runDesktop(options) == 0);  // 3 would mean validation messages

  const Image8 actual = loadImage8(options.screenshot, 4);
  const auto golden = test::sourceDir() / "tests/app/golden/desktop.png";
  if (std::getenv("VT_UPDATE_GOLDENS")) {
    savePng(golden, actual);
    WARN("golden rewritten: " << golden.string());
  }
  const Image8 expected = loadImage8(golden, 4);
  // The scene and the scripted hand are deterministic; HUD figures (frame time, haptic rate,
  // plots) change from run to run, so the tolerance is a PSNR floor plus a small fraction of
  // clearly different pixels (the HUD text).
  const Difference d = compare(actual, expected);
  INFO("PSNR " << d.psnr_db << " dB, " << d.badFraction * 100.0 << " % pixels off by > 40 (actual: "
               << options.screenshot << ")");
  CHECK(d.psnr_db > 22.0);
  CHECK(d.badFraction < 0.03);

  // The hand is drawn: skin-coloured pixels around the scripted cursor path.
  int skin = 0;
  for (int y = actual.height / 4; y < actual.height * 3 / 4; ++y) {
    for (int x = actual.width / 3; x < actual.width * 2 / 3; ++x) {
      const int r = actual.at(x, y, 0), g = actual.at(x, y, 1), b = actual.at(x, y, 2);
      skin += r > 180 && g > 120 && g < 215 && b > 90 && b < 190 && r > g && g > b;
    }
  }
  CHECK(skin > 2000);
}

namespace {

/// The index contact's per-tick UV speeds (step over the time since the previous tick: a tick
/// the scheduler delays covers more ground) over the longest stretch on one face of one object.
struct SweepSteps {
  std::vector<double> steps;  // UV per millisecond
  double meanStep = 0.0;
  double zeroFraction = 0.0;  // ticks on which the contact did not move at all
  double p99Ratio = 0.0;      // 99th percentile over the mean (1 for a steady sweep)
  int stalledTicks = 0;       // ticks left out: inside a pose gap longer than the prediction's bound
};

// Steady ticks a sweep needs before its statistics say anything.
constexpr std::size_t kEnoughSteadyTicks = 200;

SweepSteps sweepSteps(const std::filesystem::path& recording) {
  std::ifstream in(recording);
  REQUIRE(in);
  // C t_ns contact in_contact object material u v depth_m intensity (docs/app.md)
  struct Sample {
    long long t_ns;
    int contact, inContact, object;
    double u, v;
  };
  std::vector<Sample> samples;
  std::vector<long long> poses_ns;  // published pose stamps, in order
  long long handStops_ns = 0;       // stamp of the last pose that differs from the one before it
  std::string previousJoints;
  std::map<int, int> touching;  // contact -> ticks in contact
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("P ", 0) == 0) {
      std::istringstream fields(line.substr(2));
      long long t_ns, sequence;
      int valid;
      REQUIRE(fields >> t_ns >> sequence >> valid);
      std::string joints;
      std::getline(fields, joints);
      if (joints != previousJoints) handStops_ns = t_ns;
      previousJoints = joints;
      poses_ns.push_back(t_ns);
      continue;
    }
    if (line.rfind("C ", 0) != 0) continue;
    std::istringstream fields(line.substr(2));
    int material;
    Sample s;
    REQUIRE(fields >> s.t_ns >> s.contact >> s.inContact >> s.object >> material >> s.u >> s.v);
    samples.push_back(s);
    touching[s.contact] += s.inContact;
  }
  int index = 0;  // the contact that touched longest: the index fingertip on the scripted path
  for (const auto& [contact, ticks] : touching)
    if (ticks > touching[index]) index = contact;
  // The path crosses plate edges, whose side faces have their own UVs: a step of more than a
  // tenth of the map in one millisecond (10 m/s on a 10 cm plate) is a change of face, not
  // motion. The stretches between such changes are compared; the longest is the top face.
  constexpr double kFaceChange = 0.1;
  using Stretch = std::vector<std::pair<long long, double>>;  // tick time, UV per millisecond
  Stretch longest, stretch;
  const Sample* previous = nullptr;
  for (const Sample& s : samples) {
    if (s.contact != index) continue;
    const double step = previous ? std::hypot(s.u - previous->u, s.v - previous->v) : 0.0;
    if (previous && previous->inContact && s.inContact && previous->object == s.object && step < kFaceChange &&
        s.t_ns > previous->t_ns) {
      stretch.emplace_back(s.t_ns, step / (double(s.t_ns - previous->t_ns) * 1e-6));
    } else {
      if (stretch.size() > longest.size()) longest = stretch;
      stretch.clear();
    }
    previous = &s;
  }
  if (stretch.size() > longest.size()) longest = stretch;
  REQUIRE(!longest.empty());
  // The path starts from rest, presses down and stops at its end: two 60 Hz frames at each end of
  // the stretch are those transients, not the steady slide compared here. When frames come slower
  // than 60 Hz (a loaded machine) the path ends before the run's last frame and the hand rests on
  // the plate: the stretch ends where the hand stopped.
  constexpr long long kEdge_ns = 40'000'000;
  const long long first_ns = longest.front().first, last_ns = std::min(longest.back().first, handStops_ns);
  // A frame that took longer than the prediction's bound (two 60 Hz intervals plus 20 ms) leaves
  // the loop holding the hand by design: on a loaded machine that is the frame source stalling,
  // not the loop's sampling, so ticks inside such a pose gap are left out and counted.
  constexpr long long kStall_ns = 50'000'000;
  auto inStall = [&](long long t_ns) {
    const auto next = std::upper_bound(poses_ns.begin(), poses_ns.end(), t_ns);
    return next != poses_ns.begin() && next != poses_ns.end() && *next - *(next - 1) > kStall_ns;
  };
  SweepSteps out;
  for (const auto& [t_ns, speed] : longest) {
    if (t_ns <= first_ns + kEdge_ns || t_ns >= last_ns - kEdge_ns) continue;
    if (inStall(t_ns)) {
      ++out.stalledTicks;
      continue;
    }
    out.steps.push_back(speed);
  }
  if (out.steps.size() <= kEnoughSteadyTicks) return out;  // too few to judge: the caller runs again
  std::vector<double> sorted = out.steps;
  std::sort(sorted.begin(), sorted.end());
  for (double step : sorted) out.meanStep += step / double(sorted.size());
  out.zeroFraction = double(std::count(sorted.begin(), sorted.end(), 0.0)) / double(sorted.size());
  out.p99Ratio = sorted[sorted.size() * 99 / 100] / out.meanStep;
  return out;
}

}  // namespace

// The paper's consistency in the live desktop path: the scripted cursor slides steadily while
// frames come at 60 Hz or slower; the input thread reads it at 1 kHz apart from the frames, so
// the loop sweeps the surface at the hand's speed on every tick. Poses read once per frame held
// still on over 90 % of the ticks; even the newest pose (no interpolation) now moves on most.
TEST_CASE("In the desktop window the haptic loop sweeps steadily: poses come at the input rate, not per frame",
          "[.desktop]") {
  if (!app::haveDisplay()) VT_SKIP("no display (ctest runs this under xvfb-run)");
  const auto out = test::outputDir("app_desktop_sweep");
  auto run = [&](PoseSampling sampling, const char* name) {
    app::DesktopOptions options;
    options.frames = 90;  // 1.5 s of the path at 60 Hz
    options.scripted = true;
    options.width = 640;
    options.height = 360;
    options.haptic.sampling = sampling;
    options.sinks.glove = "none";
    options.sinks.record = (out / (std::string(name) + ".rec")).string();
    REQUIRE(app::runDesktop(options) == 0);
    return sweepSteps(options.sinks.record);
  };
  // On a loaded machine most of a run's ticks can fall in frame stalls (left out above); the
  // pair runs again then, up to three times, rather than judge a handful of ticks.
  SweepSteps predicted, latest;
  for (int attempt = 1; attempt <= 3; ++attempt) {
    predicted = run(PoseSampling::Predict, "predict");
    latest = run(PoseSampling::Latest, "latest");
    if (predicted.steps.size() > kEnoughSteadyTicks && latest.steps.size() > kEnoughSteadyTicks) break;
    WARN("attempt " << attempt << ": steady ticks " << predicted.steps.size() << " / " << latest.steps.size()
                    << " (left out in frame stalls: " << predicted.stalledTicks << " / " << latest.stalledTicks
                    << "): the frames stalled, so the sweep runs again");
  }
  REQUIRE(predicted.steps.size() > kEnoughSteadyTicks);
  REQUIRE(latest.steps.size() > kEnoughSteadyTicks);
  INFO("predict: " << predicted.steps.size() << " ticks, still " << predicted.zeroFraction * 100.0
                   << " %, p99 step / mean " << predicted.p99Ratio << "; latest: still " << latest.zeroFraction * 100.0
                   << " %, p99 step / mean " << latest.p99Ratio << "; ticks in frame stalls left out: "
                   << predicted.stalledTicks << " / " << latest.stalledTicks);
#ifdef VT_SANITIZER_ADDRESS
  // Under ASan a frame takes several 60 Hz periods on lavapipe, past the prediction's bounded
  // horizon: the run still checks memory safety, the timing is checked in the plain build.
  WARN("sanitizer build: frame pacing is too slow for the 60 Hz timing checks; they run in the plain build");
  return;
#endif
  CHECK(predicted.zeroFraction < 0.02);
  CHECK(predicted.p99Ratio < 1.5);  // the goal for the UV step ratio
  CHECK(latest.zeroFraction < 0.5);  // the newest pose moves too: it is at most a millisecond old
}

// --overlay: the vibration maps are drawn over the plates from the first frame, and the HUD shows
// their colour scale (bottom right); without it neither appears.
TEST_CASE("The overlay option draws the vibration maps and their colour bar from the start", "[.desktop]") {
  if (!app::haveDisplay()) VT_SKIP("no display (ctest runs this under xvfb-run)");
  const auto out = test::outputDir("app_desktop_overlay");
  // Saturated heat-red pixels (the colour bar's and the overlay's middle range) in a region.
  auto heatRed = [](const Image8& image, int x0, int y0, int x1, int y1) {
    int count = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const std::uint8_t* p = &image.pixels[(std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 4];
        count += p[0] > 180 && p[1] < 70 && p[2] < 50;
      }
    return count;
  };
  std::map<bool, Image8> shots;
  for (const bool overlay : {false, true}) {
    app::DesktopOptions options;
    options.frames = 4;
    options.width = 1280;
    options.height = 720;
    options.overlay = overlay;
    options.validate = true;
    options.sinks.glove = "none";
    options.screenshot = (out / (overlay ? "on.png" : "off.png")).string();
    REQUIRE(app::runDesktop(options) == 0);
    shots[overlay] = loadImage8(options.screenshot, 4);
  }
  const int w = shots[true].width, h = shots[true].height;
  INFO("colour bar region: " << heatRed(shots[true], w - 200, h - 90, w, h) << " red pixels with --overlay, "
                             << heatRed(shots[false], w - 200, h - 90, w, h) << " without");
  CHECK(heatRed(shots[true], w - 200, h - 90, w, h) > 50);
  CHECK(heatRed(shots[false], w - 200, h - 90, w, h) == 0);
  // The plates (the middle of the window) change colour; the same run without it is otherwise
  // the same picture (no input moves anything).
  const Difference plates = compare(shots[true], shots[false]);
  INFO("pixels changed by the overlay: " << plates.badFraction * 100.0 << " %");
  CHECK(plates.badFraction > 0.03);
}

TEST_CASE("The UI text grows with the window from 1080p, rebuilt when the window is resized", "[desktop]") {
  if (!app::haveDisplay()) VT_SKIP("no display (ctest runs this under xvfb-run)");
  std::shared_ptr<renderer::Device> device;
  {
    test::UiWindow ui(1280, 720, "text scale test");
    device = ui.device;
    const auto frame = [&] {
      float fontSize = 0.0f;
      ui.frame([&] {
        fontSize = ImGui::GetFontSize();
        ImGui::Begin("Devices");
        ImGui::TextUnformatted("frame 16.7 ms");
        ImGui::End();
      });
      return fontSize;
    };
    CHECK(frame() == 13.0f);
    glfwSetWindowSize(ui.window->window(), 1920, 1080);
    for (int i = 0; i < 20 && ui.imgui->textScale() != 1.5f; ++i) frame();  // the X server applies the size
    CHECK(frame() == 20.0f);
    CHECK(ui.imgui->textScale() == 1.5f);
    glfwSetWindowSize(ui.window->window(), 1280, 720);
    for (int i = 0; i < 20 && ui.imgui->textScale() != 1.0f; ++i) frame();
    CHECK(frame() == 13.0f);
  }
  CHECK(device->validationMessageCount() == 0);
}
