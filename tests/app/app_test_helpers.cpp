#include "app_test_helpers.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include <catch2/catch.hpp>
#include <imgui.h>
#include <imgui_internal.h>  // the context's window list

#include "modes/hand_control.hpp"
#include "vt/scene/demo_scene.hpp"
#include "vt/collision/collision_scene.hpp"
#include "vt/scene/image.hpp"
#include "vt/scene/trajectory.hpp"

namespace vt::test {

std::filesystem::path writeBandDataset(const std::filesystem::path& dir, const std::string& name, int width,
                                       int height, float bandStart, float bandEnd, double mmPerPixel) {
  const auto folder = dir / name;
  std::filesystem::create_directories(folder);
  Image8 photo(width, height, 3), map(width, height, 1);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float u = (float(x) + 0.5f) / float(width);
      const bool band = u >= bandStart && u < bandEnd;
      for (int c = 0; c < 3; ++c) photo.at(x, y, c) = band ? 60 : std::uint8_t(180 + 40 * ((x / 8 + y / 8) % 2));
      map.at(x, y, 0) = band ? 230 : 20;
    }
  }
  savePng(folder / (name + ".png"), photo);
  savePng(folder / (name + "_acc.png"), map);
  std::ofstream(folder / (name + "_map.json")) << "{\"mm_per_pixel\": " << mmPerPixel << "}\n";
  return dir;
}

std::filesystem::path writeIndexSlide(const std::filesystem::path& file, glm::vec3 from, glm::vec3 to, float press_m,
                                      double seconds) {
  // Curl only the index finger a little so its tip is the hand's lowest point.
  const FingerCurls curls{0.0f, 0.1f, 0.0f, 0.0f, 0.0f};
  const HandPose model = poseHand(palmTransform({0, 0, 0}, {0, 0, 0}), curls);
  const glm::vec3 tip = model.at(HandJoint::IndexTip);
  const float radius = model.radius_m[std::size_t(HandJoint::IndexTip)];
  auto palmFor = [&](glm::vec3 p, float lift) { return p - tip + glm::vec3(0.0f, radius - press_m + lift, 0.0f); };
  std::ofstream out(file);
  out << "t_s,x_m,y_m,z_m,curl_thumb,curl_index,curl_middle,curl_ring,curl_little\n";
  auto key = [&](double t, glm::vec3 palm) {
    out << t << ',' << palm.x << ',' << palm.y << ',' << palm.z << ",0,0.1,0,0,0\n";
  };
  key(0.0, palmFor(from, 0.02f));
  key(0.2, palmFor(from, 0.0f));
  key(0.2 + seconds, palmFor(to, 0.0f));
  key(0.4 + seconds, palmFor(to, 0.02f));
  return file;
}

std::vector<TraceRow> readTraces(const std::filesystem::path& csv) {
  std::ifstream in(csv);
  REQUIRE(in);
  std::string line;
  std::getline(in, line);
  REQUIRE(line == "time_s,finger,contact,material,u,v,depth_m,map_value,intensity,across_weight");
  std::vector<TraceRow> rows;
  while (std::getline(in, line)) {
    std::stringstream s(line);
    std::string field;
    TraceRow r;
    std::getline(s, field, ',');
    r.t_s = std::stod(field);
    std::getline(s, r.finger, ',');
    std::getline(s, field, ',');
    r.contact = field == "1";
    std::getline(s, r.material, ',');
    float* values[] = {&r.u, &r.v, &r.depth_m, &r.mapValue, &r.intensity};
    for (float* v : values) {
      std::getline(s, field, ',');
      *v = std::stof(field);
    }
    rows.push_back(r);
  }
  return rows;
}

float ScreenBox::area() const { return std::max(0.0f, max.x - min.x) * std::max(0.0f, max.y - min.y); }

float ScreenBox::overlap(const ScreenBox& other) const {
  const ScreenBox shared{"", glm::max(min, other.min), glm::min(max, other.max)};
  return shared.area();
}

ScreenBox projectBox(const CameraView& view, glm::vec2 size_px, const std::vector<glm::vec3>& points_world) {
  const glm::mat4 clipFromWorld = view.projection() * view.view();
  ScreenBox box{"", glm::vec2(1e9f), glm::vec2(-1e9f)};
  for (const glm::vec3& p : points_world) {
    const glm::vec4 clip = clipFromWorld * glm::vec4(p, 1.0f);
    REQUIRE(clip.w > 0.0f);  // in front of the camera
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;  // Vulkan: y down, -1 at the top
    const glm::vec2 px = (ndc + 1.0f) * 0.5f * size_px;
    box.min = glm::min(box.min, px);
    box.max = glm::max(box.max, px);
  }
  box.min = glm::clamp(box.min, glm::vec2(0.0f), size_px);
  box.max = glm::clamp(box.max, glm::vec2(0.0f), size_px);
  return box;
}

namespace {

// The eight corners of an axis-aligned box.
void addCorners(glm::vec3 lo, glm::vec3 hi, const glm::mat4& T, std::vector<glm::vec3>& out) {
  for (int c = 0; c < 8; ++c) {
    const glm::vec3 corner{c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z};
    out.push_back(glm::vec3(T * glm::vec4(corner, 1.0f)));
  }
}

}  // namespace

std::vector<ScreenBox> touchableObjectBoxes(const Scene& scene, glm::vec2 size_px) {
  const CameraView view = scene.camera.view(size_px.x / size_px.y);
  std::vector<ScreenBox> boxes;
  for (const SceneObject& object : scene.objects) {
    if (object.material < 0 || scene.materials[std::size_t(object.material)].vibrationMap < 0) continue;
    const Aabb b = bounds(scene.meshes[std::size_t(object.mesh)]);
    std::vector<glm::vec3> corners;
    addCorners(b.min, b.max, object.T_world_object, corners);
    boxes.push_back(projectBox(view, size_px, corners));
    boxes.back().name = object.name;
  }
  return boxes;
}

std::vector<ScreenBox> desktopHandBoxes(const app::LoadedScene& scene, glm::vec2 size_px) {
  const collision::CollisionScene& world = *scene.haptic->collision;
  const CameraView view = scene.scene->camera.view(size_px.x / size_px.y);
  const auto box = [&](const app::DesktopHand& hand, const char* name) {
    const HandPose pose = app::visualProxy(hand.pose(false, 0), world);
    std::vector<glm::vec3> corners;
    for (int j = 0; j < kHandJointCount; ++j) {
      const glm::vec3 r(std::max(pose.radius_m[std::size_t(j)], kDefaultFingertipRadius_m));
      addCorners(pose.position[std::size_t(j)] - r, pose.position[std::size_t(j)] + r, glm::mat4(1.0f), corners);
    }
    ScreenBox out = projectBox(view, size_px, corners);
    out.name = name;
    return out;
  };
  app::DesktopHand hand;
  std::vector<ScreenBox> boxes = {box(hand, "hand at its start pose")};
  const glm::vec3 forward = glm::vec3(view.T_world_eye * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f));
  hand.placeIndexTipOver(app::pickSurface(world, view.position(), forward));
  boxes.push_back(box(hand, "hand under the mouse at the centre"));
  return boxes;
}

std::vector<ScreenBox> visibleImGuiWindows() {
  std::vector<ScreenBox> boxes;
  for (const ImGuiWindow* w : ImGui::GetCurrentContext()->Windows) {
    // Active: begun this frame (the unused implicit "Debug" window is not); Hidden: auto-sizing.
    if (!w->Active || w->Hidden || w->ParentWindow || (w->Flags & ImGuiWindowFlags_Tooltip)) continue;
    boxes.push_back({w->Name, {w->Pos.x, w->Pos.y}, {w->Pos.x + w->Size.x, w->Pos.y + w->Size.y}});
  }
  return boxes;
}

UiWindow::UiWindow(int width, int height, const char* title) {
  renderer::DeviceOptions deviceOptions;
  deviceOptions.validate = true;
  renderer::addWindowExtensions(deviceOptions);
  device = renderer::Device::create(deviceOptions);
  gpu = std::make_unique<renderer::Renderer>(device);
  gpu->setScene(std::make_shared<const Scene>(makeDemoScene()));
  window = std::make_unique<renderer::WindowTarget>(device, renderer::WindowOptions{.width = width, .height = height, .title = title, .vsync = false});
  imgui = std::make_unique<renderer::ImGuiLayer>(*gpu, *window);
}

UiWindow::~UiWindow() {
  gpu->waitIdle();
  imgui.reset();
  window.reset();
  gpu.reset();
}

Image8 UiWindow::frame(const std::function<void()>& ui, bool capture) {
  window->pollEvents();
  imgui->beginFrame();
  ui();
  imgui->endFrame();
  renderer::FrameDesc desc;
  const VkExtent2D extent = window->extent();
  desc.views = {makeDemoScene().camera.view(float(extent.width) / float(std::max(1u, extent.height)))};
  if (capture) window->requestCapture();
  // A frame skipped while the swapchain is recreated (a resize) is drawn again.
  for (int tries = 0; tries < 100 && !gpu->render(*window, desc); ++tries) window->pollEvents();
  return capture ? window->takeCapture() : Image8{};
}

}  // namespace vt::test
