// The HUD's docked layout on a headless ImGui context (no window, no GPU): where the panels go
// at 1280x720, what is collapsed by default, and an undocked panel kept through the ini text;
// where the ini file goes.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <string>

#include <imgui.h>
#include <imgui_internal.h>

#include "modes/session_hud.hpp"
#include "test_support.hpp"
#include "ui/hud.hpp"
#include "ui/hud_layout.hpp"

namespace {

// One ImGui context sized like the default window, with its font atlas built (NewFrame needs it).
struct HeadlessImGui {
  explicit HeadlessImGui(const char* ini = nullptr) {
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = {1280, 720};
    io.DeltaTime = 1.0f / 60.0f;
    unsigned char* pixels = nullptr;
    int w = 0, h = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
    vt::ui::installHudLayout();
    if (ini) ImGui::LoadIniSettingsFromMemory(ini);
  }
  ~HeadlessImGui() { ImGui::DestroyContext(); }

  // Draws the HUD for a few frames (auto-sizing settles over two) with one long material name.
  void drawFrames(vt::ui::HudSettings& settings, int frames = 3) {
    std::vector<float> history(60, 0.1f);
    std::vector<vt::ui::HudContact> contacts(5);
    for (int f = 0; f < 5; ++f) contacts[std::size_t(f)].finger = f, contacts[std::size_t(f)].history = &history;
    contacts[1].inContact = true;
    contacts[1].material = "a_really_long_material_name_from_a_published_dataset_folder";
    contacts[1].depth_m = 0.004f;
    contacts[1].intensity = 0.42f;
    vt::ui::HudStatus status;
    status.scene = "assets (8 objects)";
    for (int i = 0; i < frames; ++i) {
      ImGui::NewFrame();
      vt::ui::drawHud(status, contacts, {}, settings);
      ImGui::Render();
    }
  }

  static ImGuiWindow& window(const char* id) {
    ImGuiWindow* w = ImGui::FindWindowByName(id);
    REQUIRE(w != nullptr);
    return *w;
  }
};

}  // namespace

TEST_CASE("HUD: touch docked top-left, devices/settings/glove stacked top-right and collapsed") {
  HeadlessImGui gui;
  vt::ui::HudSettings settings;
  settings.help = false;
  gui.drawFrames(settings);
  const ImGuiWindow& touch = HeadlessImGui::window("Touch");
  CHECK(touch.Pos.x == Approx(8.0f));
  CHECK(touch.Pos.y == Approx(8.0f));
  CHECK_FALSE(touch.Collapsed);
  CHECK(touch.Size.x < 360.0f);  // a long material name does not widen the panel
  float below = 0.0f;
  for (const char* id : {"###Devices", "###Settings", "###Glove"}) {
    const ImGuiWindow& w = HeadlessImGui::window(id);
    INFO(id);
    CHECK(w.Collapsed);
    CHECK(w.Pos.x + w.Size.x == Approx(1272.0f));  // right edge, 8 px margin
    CHECK(w.Pos.y >= below);                         // stacked, not overlapping
    CHECK(w.Size.y < 30.0f);                         // one title line
    below = w.Pos.y + w.Size.y;
  }
  // The three collapsed panels use the top 100 pixels of the right edge only.
  CHECK(below < 100.0f);
}

TEST_CASE("HUD: an undocked panel stays where the user left it, through the ini, until docked again") {
  const char* ini =
      "[Window][###Devices]\nPos=300,400\nSize=360,200\nCollapsed=0\n\n"
      "[VTouchingPanel][###Devices]\ndocked=0\n\n";
  HeadlessImGui gui(ini);
  vt::ui::HudSettings settings;
  gui.drawFrames(settings);
  const ImGuiWindow& devices = HeadlessImGui::window("###Devices");
  CHECK(devices.Pos.x == Approx(300.0f));
  CHECK(devices.Pos.y == Approx(400.0f));
  CHECK_FALSE(devices.Collapsed);  // saved state wins over the default
  // Settings takes the top-right slot Devices left.
  CHECK(HeadlessImGui::window("###Settings").Pos.y == Approx(8.0f));
  const std::string saved = ImGui::SaveIniSettingsToMemory();
  CHECK(saved.find("[VTouchingPanel][###Devices]\ndocked=0") != std::string::npos);
  CHECK(saved.find("[VTouchingPanel][###Settings]\ndocked=1") != std::string::npos);

  vt::ui::dockAllPanels();
  gui.drawFrames(settings);
  CHECK(devices.Pos.y == Approx(8.0f));
  CHECK(devices.Pos.x + devices.Size.x == Approx(1272.0f));
  CHECK(std::string(ImGui::SaveIniSettingsToMemory()).find("[VTouchingPanel][###Devices]\ndocked=1") != std::string::npos);
}

TEST_CASE("HUD: the layout file lives in the user's config folder, which is created") {
  const auto dir = vt::test::outputDir("hud_settings_file") / "config";
  std::filesystem::remove_all(dir);
  const char* saved = std::getenv("XDG_CONFIG_HOME");
  const std::string restore = saved ? saved : "";
  ::setenv("XDG_CONFIG_HOME", dir.c_str(), 1);
  const std::string file = vt::app::hudSettingsFile();
  if (saved) ::setenv("XDG_CONFIG_HOME", restore.c_str(), 1); else ::unsetenv("XDG_CONFIG_HOME");
  CHECK(file == (dir / "vtouching" / "imgui.ini").string());
  CHECK(std::filesystem::is_directory(dir / "vtouching"));
}
