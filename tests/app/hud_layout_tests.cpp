// The HUD's docked layout on a headless ImGui context (no window, no GPU): where the panels go
// at 1280x720 and what they leave visible of the desktop scene (plates, the hand), what is
// collapsed by default, the depth readout next to a long name, the stale-poses tooltip, an
// undocked panel kept through the ini text, and the layout kept across a restart.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <string>

#include <imgui.h>
#include <imgui_internal.h>

#include "app_test_helpers.hpp"
#include "modes/scene_source.hpp"
#include "modes/touch_hud.hpp"
#include "test_support.hpp"
#include "ui/hud.hpp"
#include "ui/hud_layout.hpp"
#include "ui/recent_rate.hpp"
#include "vt/renderer/imgui_layer.hpp"

namespace {

constexpr const char* kLongName = "a_really_long_material_name_from_a_published_dataset_folder_";  // 60 characters

// The HUD's contact lines: five fingers with plots, the index touching `material` 4 mm deep.
struct TouchLines {
  explicit TouchLines(std::string material = kLongName) : history(60, 0.1f), contacts(5) {
    for (int f = 0; f < 5; ++f) contacts[std::size_t(f)].finger = f, contacts[std::size_t(f)].history = &history;
    contacts[1].inContact = true;
    contacts[1].material = std::move(material);
    contacts[1].depth_m = 0.004f;
    contacts[1].intensity = 0.42f;
  }
  TouchLines(const TouchLines&) = delete;  // the contacts point at history
  std::vector<float> history;
  std::vector<vt::ui::HudContact> contacts;
};

// One ImGui context sized like the default window, with its font atlas built (NewFrame needs it).
// `iniFile`: ImGui reads it at the first frame and writes it when the context ends, as the app's.
struct HeadlessImGui {
  explicit HeadlessImGui(const char* ini = nullptr, const std::string& iniFile = {}, ImVec2 display = {1280, 720})
      : m_iniFile(iniFile) {
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = m_iniFile.empty() ? nullptr : m_iniFile.c_str();
    io.DisplaySize = display;
    io.DeltaTime = 1.0f / 60.0f;
    // The font the ImGuiLayer builds for a window this high (13 px up to 899 px high).
    ImFontConfig font;
    font.SizePixels = std::round(13.0f * vt::renderer::textScaleForHeight(int(display.y)));
    io.Fonts->AddFontDefault(&font);
    ImGui::GetStyle().ScaleAllSizes(vt::renderer::textScaleForHeight(int(display.y)));
    unsigned char* pixels = nullptr;
    int w = 0, h = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
    vt::ui::installHudLayout();
    if (ini) ImGui::LoadIniSettingsFromMemory(ini);
  }
  ~HeadlessImGui() { ImGui::DestroyContext(); }

  // Draws the HUD for a few frames (auto-sizing settles over two).
  void drawFrames(vt::ui::HudSettings& settings, int frames = 3, const TouchLines& lines = TouchLines()) {
    vt::ui::HudStatus status;
    status.scene = "assets (8 objects)";
    for (int i = 0; i < frames; ++i) {
      ImGui::NewFrame();
      vt::ui::drawHud(status, lines.contacts, {}, settings);
      ImGui::Render();
    }
  }

  static ImGuiWindow& window(const char* id) {
    ImGuiWindow* w = ImGui::FindWindowByName(id);
    REQUIRE(w != nullptr);
    return *w;
  }

 private:
  std::string m_iniFile;  // ImGui keeps the pointer
};

// A character as the frame draws it: its quad, where the font's pen was, and whether its draw
// command's clip rectangle (the window, a table column) shows all of it.
struct Glyph {
  char c = 0;
  ImVec2 min, max;
  ImVec2 pen;
  float advance = 0.0f;
  bool visible = false;
};

// The text a window drew in the frame just rendered, read back from its draw list: every quad
// textured with one of the font's glyphs, in reading order (a glyph cut by the CPU clipper has
// other texture coordinates and is missed, so it counts as not visible).
std::vector<Glyph> drawnGlyphs(const ImGuiWindow& window) {
  const ImFont* font = ImGui::GetIO().Fonts->Fonts[0];
  std::map<std::array<float, 4>, const ImFontGlyph*> byUv;
  for (char c = 33; c < 127; ++c)
    if (const ImFontGlyph* g = font->FindGlyphNoFallback(ImWchar(c))) byUv[{g->U0, g->V0, g->U1, g->V1}] = g;
  std::vector<Glyph> out;
  const ImDrawList& list = *window.DrawList;
  for (const ImDrawCmd& cmd : list.CmdBuffer) {
    // ImFont::RenderText writes one quad per glyph: vertices a b c d, indices a b c a c d.
    for (unsigned i = cmd.IdxOffset; i + 6 <= cmd.IdxOffset + cmd.ElemCount;) {
      const ImDrawIdx* idx = &list.IdxBuffer[int(i)];
      const bool quad = idx[1] == idx[0] + 1 && idx[2] == idx[0] + 2 && idx[3] == idx[0] && idx[4] == idx[0] + 2 &&
                        idx[5] == idx[0] + 3;
      const ImDrawVert& a = list.VtxBuffer[int(cmd.VtxOffset + idx[0])];
      const ImDrawVert& c = list.VtxBuffer[int(cmd.VtxOffset + idx[0] + (quad ? 2 : 0))];
      const auto found = quad ? byUv.find({a.uv.x, a.uv.y, c.uv.x, c.uv.y}) : byUv.end();
      if (found == byUv.end()) {
        i += 3;  // a triangle of something else
        continue;
      }
      const ImFontGlyph& g = *found->second;
      const ImVec4& clip = cmd.ClipRect;
      out.push_back({char(g.Codepoint), a.pos, c.pos, {a.pos.x - g.X0, a.pos.y - g.Y0}, g.AdvanceX,
                     a.pos.x >= clip.x && a.pos.y >= clip.y && c.pos.x <= clip.z && c.pos.y <= clip.w});
      i += 6;
    }
  }
  // Reading order (a table draws its columns one after the other).
  std::stable_sort(out.begin(), out.end(), [](const Glyph& a, const Glyph& b) {
    return std::lround(a.pen.y) != std::lround(b.pen.y) ? a.pen.y < b.pen.y : a.pen.x < b.pen.x;
  });
  return out;
}

// The glyphs as text: a line break where the pen goes to another line, one space for any gap
// (columns), '#' for a glyph not fully shown.
std::string drawnText(const std::vector<Glyph>& glyphs) {
  std::string text;
  const Glyph* previous = nullptr;
  for (const Glyph& g : glyphs) {
    if (previous) {
      if (std::lround(g.pen.y) != std::lround(previous->pen.y)) text += '\n';
      else if (g.pen.x > previous->pen.x + previous->advance + 0.5f) text += ' ';
    }
    text += g.visible ? g.c : '#';
    previous = &g;
  }
  return text;
}

// The first glyph of `word` in a window's drawn text (REQUIREs it).
const Glyph& findWord(const std::vector<Glyph>& glyphs, const std::string& word) {
  const std::string text = drawnText(glyphs);
  // drawnText adds one character per glyph plus separators: map the text offset back.
  std::size_t at = text.find(word);
  INFO("drawn text:\n" << text);
  REQUIRE(at != std::string::npos);
  std::size_t glyph = 0;
  for (std::size_t i = 0; i < at; ++i)
    if (text[i] != ' ' && text[i] != '\n') ++glyph;
  return glyphs[glyph];
}

std::string oneLine(std::string text) {
  for (char& c : text)
    if (c == '\n') c = ' ';
  return text;
}

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

TEST_CASE("HUD: the Devices panel keeps its size as its figures change, so the panels below it stay put") {
  HeadlessImGui gui("[Window][###Devices]\nCollapsed=0\n\n");
  vt::ui::HudSettings settings;
  settings.help = false;
  const TouchLines lines;
  // Two moments of one session: figures of other widths, a timing line that wraps differently.
  vt::ui::HudStatus calm, busy;
  for (vt::ui::HudStatus* s : {&calm, &busy}) {
    s->scene = "assets ../assets/dataset (8 objects, intensity absolute)";
    s->vulkanDevice = "llvmpipe (LLVM 15.0.6, 256 bits) (CPU)";
    s->glove = "simulated glove: 1000 reports/s";
    s->realtime = "haptic loop: SCHED_FIFO 20";
  }
  calm.frame_ms = 16.7, calm.hapticRate_hz = 1000.0, calm.loop.tickP50_us = 4, calm.loop.tickP99_us = 9;
  calm.timing = "poses 60 Hz, newest age 3.2 ms, predict; drawn vs felt tip 0.12 mm (max 1.40)";
  busy.frame_ms = 123.4, busy.hapticRate_hz = std::numeric_limits<double>::quiet_NaN(), busy.loop.tickP50_us = 1234;
  busy.loop.tickP99_us = 23456, busy.loop.jitterP99_us = 34567, busy.overrunRate_hz = 123.4, busy.stalePoseRate_hz = 56.7;
  busy.timing = "poses 120 Hz, newest ahead 13.2 ms, interpolate (delayed); drawn vs felt tip 10.12 mm (max 21.40)";
  const auto draw = [&](const vt::ui::HudStatus& status) {
    for (int i = 0; i < 3; ++i) {
      ImGui::NewFrame();
      vt::ui::drawHud(status, lines.contacts, {}, settings);
      ImGui::Render();
    }
    const ImGuiWindow& devices = HeadlessImGui::window("###Devices");
    return std::array<float, 3>{devices.Size.x, devices.Size.y, HeadlessImGui::window("###Settings").Pos.y};
  };
  draw(calm);
  const auto first = draw(busy);  // a longer line may wrap once more: the panel grows once
  for (int round = 0; round < 3; ++round) {
    INFO("round " << round);
    CHECK(draw(calm) == first);
    CHECK(draw(busy) == first);
  }
  REQUIRE_FALSE(HeadlessImGui::window("###Devices").Collapsed);
}

TEST_CASE("HUD: overruns and stale poses read as a rate over the last seconds, not a total since start") {
  vt::ui::RecentRate rate(5.0);
  const std::int64_t s = 1'000'000'000;
  CHECK(rate.update(0, 0) == 0.0);
  CHECK(rate.update(s / 2, 1000) == Approx(2000.0));  // a burst at start-up
  double after = -1.0;
  for (int i = 1; i <= 100; ++i) after = rate.update(s / 2 + std::int64_t(i) * s / 10, 1000);  // 10 s calm
  CHECK(after == 0.0);  // the burst has left the window
  for (int i = 1; i <= 100; ++i) after = rate.update(s * 21 / 2 + std::int64_t(i) * s / 10, 1000 + std::uint64_t(i) / 2);
  CHECK(after == Approx(5.0).margin(0.3));  // 5 per second now
  CHECK(rate.update(s * 21, 3) == 0.0);     // the loop restarted (settings changed): counted afresh

  HeadlessImGui gui("[Window][###Devices]\nCollapsed=0\n\n");
  vt::ui::HudSettings settings;
  vt::ui::HudStatus status;
  status.loop.overruns = 123456;  // totals since start ...
  status.loop.stalePoses = 7890;
  status.overrunRate_hz = 0.0;    // ... but nothing lately
  status.stalePoseRate_hz = 2.5;
  const TouchLines lines;
  for (int i = 0; i < 3; ++i) {
    ImGui::NewFrame();
    vt::ui::drawHud(status, lines.contacts, {}, settings);
    ImGui::Render();
  }
  const std::string text = oneLine(drawnText(drawnGlyphs(HeadlessImGui::window("###Devices"))));
  INFO(text);
  CHECK(text.find("overruns 0.0/s") != std::string::npos);
  CHECK(text.find("stale poses 2.5/s") != std::string::npos);
  CHECK(text.find("123456") == std::string::npos);
}

TEST_CASE("HUD: the text grows with the window from 1080p, and the panels with it") {
  CHECK(vt::renderer::textScaleForHeight(720) == 1.0f);
  CHECK(vt::renderer::textScaleForHeight(899) == 1.0f);
  CHECK(vt::renderer::textScaleForHeight(1080) == 1.5f);
  CHECK(vt::renderer::textScaleForHeight(1440) == 2.0f);
  CHECK(vt::renderer::textScaleForHeight(2160) == 3.0f);
  CHECK(vt::renderer::textScaleForHeight(0) == 1.0f);
  std::array<float, 2> touchWidth{}, titleHeight{};
  for (int i = 0; i < 2; ++i) {
    HeadlessImGui gui(nullptr, {}, i == 0 ? ImVec2{1280, 720} : ImVec2{1920, 1080});
    vt::ui::HudSettings settings;
    gui.drawFrames(settings);
    CHECK(ImGui::GetFontSize() == (i == 0 ? 13.0f : 20.0f));
    touchWidth[std::size_t(i)] = HeadlessImGui::window("Touch").Size.x;
    titleHeight[std::size_t(i)] = HeadlessImGui::window("###Devices").Size.y;
  }
  CHECK(touchWidth[1] == Approx(1.5f * touchWidth[0]).epsilon(0.05));
  CHECK(titleHeight[1] == Approx(1.5f * titleHeight[0]).epsilon(0.1));
}

// What the user sees at the default window size: the panels' rectangles from ImGui against the
// plates and the hand as the desktop mode's camera projects them. Panels may cover at most 5 %
// of any plate's box (the corner of an outer plate; none in today's scenes) and nothing of the
// hand; they do not overlap each other.
TEST_CASE("HUD: at 1280x720 the default layout leaves the hand and the plates of each scene visible") {
  constexpr float kMaxPlateCover = 0.05f;
  const glm::vec2 size_px{1280.0f, 720.0f};
  std::vector<std::pair<std::string, vt::app::SceneOptions>> scenes = {{"built-in", {}}, {"default assets", {}}};
  scenes[0].second.builtin = true;
  if (const auto dataset = vt::test::datasetDir()) {
    scenes.emplace_back("published dataset", vt::app::SceneOptions{});
    scenes.back().second.dataset = dataset->string();
  } else {
    WARN("published dataset not found: its scene is not checked");
  }
  for (const bool overlay : {false, true}) {  // the overlay adds its colour bar bottom-right
    HeadlessImGui gui;
    vt::ui::HudSettings settings;  // the desktop's defaults: controls help on
    settings.overlay = overlay;
    gui.drawFrames(settings);
    const std::vector<vt::test::ScreenBox> panels = vt::test::visibleImGuiWindows();
    CHECK(panels.size() == (overlay ? 6u : 5u));  // touch, devices, settings, glove, controls (+ colour bar)
    for (std::size_t a = 0; a < panels.size(); ++a)
      for (std::size_t b = a + 1; b < panels.size(); ++b) {
        INFO(panels[a].name << " and " << panels[b].name);
        CHECK(panels[a].overlap(panels[b]) == 0.0f);
      }
    for (const auto& [label, options] : scenes) {
      const vt::app::LoadedScene scene = vt::app::loadScene(options);
      for (const vt::test::ScreenBox& hand : vt::test::desktopHandBoxes(scene, size_px)) {
        INFO(label << (overlay ? ", overlay on" : "") << ": " << hand.name << " at " << hand.min.x << "," << hand.min.y
                   << " .. " << hand.max.x << "," << hand.max.y);
        REQUIRE(hand.area() > 1000.0f);  // on screen
        for (const vt::test::ScreenBox& panel : panels) {
          INFO(panel.name << " at " << panel.min.x << "," << panel.min.y << " .. " << panel.max.x << "," << panel.max.y);
          CHECK(panel.overlap(hand) == 0.0f);
        }
      }
      const std::vector<vt::test::ScreenBox> plates = vt::test::touchableObjectBoxes(*scene.scene, size_px);
      REQUIRE(plates.size() >= 2);
      for (const vt::test::ScreenBox& plate : plates) {
        REQUIRE(plate.area() > 0.0f);
        float covered = 0.0f;  // the panels do not overlap each other: their shares add up
        for (const vt::test::ScreenBox& panel : panels) covered += panel.overlap(plate);
        INFO(plate.name << " at " << plate.min.x << "," << plate.min.y << " .. " << plate.max.x << "," << plate.max.y
                        << ": " << 100.0f * covered / plate.area() << " % under panels");
        CHECK(covered / plate.area() <= kMaxPlateCover);
      }
    }
  }
}

TEST_CASE("HUD: a 60-character material name is elided and leaves the touch line's depth and level readouts whole") {
  REQUIRE(std::string(kLongName).size() == 60);
  vt::ui::HudSettings settings;
  // Where the depth readout starts on the index's line (the glyphs of "4.0 mm 0.42" are all
  // whole: a cut one would read '#').
  const auto depthAt = [&](const std::string& material, float acrossWeight = -1.0f) {
    HeadlessImGui gui;
    TouchLines lines(material);
    lines.contacts[1].acrossWeight = acrossWeight;
    gui.drawFrames(settings, 3, lines);
    const ImGuiWindow& touch = HeadlessImGui::window("Touch");
    const std::vector<Glyph> glyphs = drawnGlyphs(touch);
    const std::string text = drawnText(glyphs);
    INFO("touch panel text:\n" << text);
    // The name's start is readable; a name too long for its column ends in "..." (no glyph cut).
    const bool fits = material.size() < 20;
    CHECK(text.find("index " + material.substr(0, fits ? material.size() : 8)) != std::string::npos);
    CHECK(text.find('#') == std::string::npos);
    const std::string direction = acrossWeight >= 0.0f ? " across 80%" : "";
    CHECK((text.find("..." + direction + " 4.0 mm 0.42") != std::string::npos) == !fits);
    const Glyph& depth = findWord(glyphs, "4.0 mm 0.42");
    CHECK(depth.min.x >= touch.Pos.x);
    CHECK(depth.pen.x + 11 * depth.advance <= touch.Pos.x + touch.Size.x);  // inside the panel
    return depth.pen.x;
  };
  const float longName = depthAt(kLongName);
  // Where a short name puts it: the long name does not push the readout aside.
  CHECK(longName == Approx(depthAt("paper")));
  // A material scanned in two directions keeps its direction share after the elided name.
  CHECK(longName == Approx(depthAt(kLongName, 0.8f)));
}

// Hovering "stale poses" in the open Devices panel explains the counter.
TEST_CASE("HUD: the stale-poses counter has a tooltip saying what it counts and what the glove does") {
  HeadlessImGui gui("[Window][###Devices]\nCollapsed=0\n\n");
  vt::ui::HudSettings settings;
  settings.haptic.poseTimeout_ms = 150.0f;
  gui.drawFrames(settings);
  const ImGuiWindow& devices = HeadlessImGui::window("###Devices");
  REQUIRE_FALSE(devices.Collapsed);
  const std::vector<Glyph> glyphs = drawnGlyphs(devices);
  const Glyph stale = findWord(glyphs, "stale poses");
  CHECK(stale.visible);
  const auto tooltip = [] {
    for (const ImGuiWindow* w : ImGui::GetCurrentContext()->Windows)
      if (w->Active && (w->Flags & ImGuiWindowFlags_Tooltip)) return oneLine(drawnText(drawnGlyphs(*w)));
    return std::string();
  };
  CHECK(tooltip().empty());  // the mouse is elsewhere
  ImGui::GetIO().MousePos = {(stale.min.x + stale.max.x) * 0.5f, (stale.min.y + stale.max.y) * 0.5f};
  gui.drawFrames(settings, 2);
  const std::string text = tooltip();
  INFO("tooltip: " << text);
  CHECK(text.find("no valid hand pose") != std::string::npos);            // what a stale pose is
  CHECK(text.find("older than the pose timeout (150 ms)") != std::string::npos);  // the timeout in use
  CHECK(text.find("hand tracking lost") != std::string::npos);            // why it happens
  CHECK(text.find("slow or lossy network") != std::string::npos);
  CHECK(text.find("actuators stay silent") != std::string::npos);         // what the glove does
  CHECK(text.find('#') == std::string::npos);                              // all of it on screen
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

// The user opens Devices and collapses Touch with the mouse (double-clicks on their titles),
// quits, and starts again: the panels come back as left, still docked, the others as default.
TEST_CASE("HUD: opened and collapsed panels come back so after a restart, through the ini file") {
  const auto file = vt::test::outputDir("hud_restart") / "imgui.ini";
  vt::ui::HudSettings settings;
  settings.help = false;
  {
    HeadlessImGui gui(nullptr, file.string());
    gui.drawFrames(settings);
    const auto doubleClickTitle = [&](const char* id) {
      const ImGuiWindow& w = HeadlessImGui::window(id);
      ImGui::GetIO().MousePos = {w.Pos.x + w.Size.x * 0.5f, w.Pos.y + w.TitleBarHeight() * 0.5f};
      gui.drawFrames(settings, 1);  // hover
      for (const bool down : {true, false, true, false}) {
        ImGui::GetIO().MouseDown[0] = down;
        gui.drawFrames(settings, 1);
      }
    };
    doubleClickTitle("###Devices");
    doubleClickTitle("Touch");
    ImGui::GetIO().MousePos = {640, 360};
    gui.drawFrames(settings);
    REQUIRE_FALSE(HeadlessImGui::window("###Devices").Collapsed);
    REQUIRE(HeadlessImGui::window("Touch").Collapsed);
  }  // the context ends and writes the file
  REQUIRE(std::filesystem::exists(file));
  HeadlessImGui gui(nullptr, file.string());
  gui.drawFrames(settings);
  const ImGuiWindow& devices = HeadlessImGui::window("###Devices");
  const ImGuiWindow& touch = HeadlessImGui::window("Touch");
  const ImGuiWindow& settingsPanel = HeadlessImGui::window("###Settings");
  CHECK_FALSE(devices.Collapsed);
  CHECK(devices.Size.y > 100.0f);
  CHECK(touch.Collapsed);
  CHECK(touch.Pos.x == Approx(8.0f));
  CHECK(settingsPanel.Collapsed);
  CHECK(HeadlessImGui::window("###Glove").Collapsed);
  // Docked: Devices at the top right, Settings stacked below the opened panel.
  CHECK(devices.Pos.y == Approx(8.0f));
  CHECK(devices.Pos.x + devices.Size.x == Approx(1272.0f));
  CHECK(settingsPanel.Pos.y >= devices.Pos.y + devices.Size.y);
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

TEST_CASE("HUD: a rate not measured yet reads '--', a stopped loop reads 0 Hz") {
  CHECK(vt::ui::rateText(std::numeric_limits<double>::quiet_NaN()) == "-- Hz");
  CHECK(vt::ui::rateText(0.0) == "0 Hz");
  CHECK(vt::ui::rateText(995.4) == "995 Hz");
}
