#pragma once
// Shared by the app tests: synthetic datasets, straight-slide trajectories and trace parsing.
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "modes/scene_source.hpp"
#include "vt/renderer/device.hpp"
#include "vt/renderer/imgui_layer.hpp"
#include "vt/renderer/renderer.hpp"
#include "vt/renderer/window_target.hpp"
#include "vt/scene/image.hpp"
#include "vt/scene/camera.hpp"
#include "vt/scene/hand.hpp"
#include "vt/scene/scene.hpp"

namespace vt::test {

/// Writes DIR/NAME/NAME.png (grey photo) and NAME_acc.png (dark, with a bright band of columns
/// [bandStart, bandEnd) of the width), plus NAME_map.json with mm_per_pixel. Returns DIR.
std::filesystem::path writeBandDataset(const std::filesystem::path& dir, const std::string& name, int width,
                                       int height, float bandStart, float bandEnd, double mmPerPixel);

/// A CSV trajectory sliding the index fingertip (others straight, above it) from `from` to `to`
/// (world, metres) pressing `press_m` into a surface at height surface_y over `seconds`.
std::filesystem::path writeIndexSlide(const std::filesystem::path& file, glm::vec3 from, glm::vec3 to, float press_m,
                                      double seconds);

/// One row of traces.csv.
struct TraceRow {
  double t_s = 0;
  std::string finger, material;
  bool contact = false;
  float u = 0, v = 0, depth_m = 0, mapValue = 0, intensity = 0;
};
std::vector<TraceRow> readTraces(const std::filesystem::path& csv);

/// A rectangle on the screen, pixels, y down (empty when max <= min on an axis).
struct ScreenBox {
  std::string name;
  glm::vec2 min{0.0f}, max{0.0f};
  float area() const;
  /// The area shared with `other`.
  float overlap(const ScreenBox& other) const;
};

/// The box around `points_world` as `view` draws them in an image of `size_px`, clipped to it.
ScreenBox projectBox(const CameraView& view, glm::vec2 size_px, const std::vector<glm::vec3>& points_world);
/// The boxes of the scene's touchable objects (a material with a vibration map: the plates, not
/// the table) from its desktop camera, named after the object.
std::vector<ScreenBox> touchableObjectBoxes(const Scene& scene, glm::vec2 size_px);
/// The desktop hand's boxes from the scene's desktop camera (every joint's sphere): at its start
/// pose, and with the index over the window's centre (where the mouse puts it when it enters there).
std::vector<ScreenBox> desktopHandBoxes(const app::LoadedScene& scene, glm::vec2 size_px);
/// Every top-level ImGui window drawn in the frame just rendered (no tooltips), named by its
/// ImGui name; call after ImGui::Render().
std::vector<ScreenBox> visibleImGuiWindows();

/// A window on a new validated device with the demo scene's renderer and Dear ImGui, for the
/// window tests run under xvfb-run. Keep `device` to read its validation count afterwards.
struct UiWindow {
  UiWindow(int width, int height, const char* title);
  ~UiWindow();  // waits for the GPU
  /// One frame: window events, `ui` inside ImGui's frame, the scene from its desktop camera;
  /// the window's image when `capture` (else empty).
  Image8 frame(const std::function<void()>& ui, bool capture = false);

  std::shared_ptr<renderer::Device> device;
  std::unique_ptr<renderer::Renderer> gpu;
  std::unique_ptr<renderer::WindowTarget> window;
  std::unique_ptr<renderer::ImGuiLayer> imgui;
};

}  // namespace vt::test
