#include "ui/hud_layout.hpp"

#include <array>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>

#include <imgui.h>
#include <imgui_internal.h>  // settings handlers and the window being dragged (ImGui 1.86 has no public API)

namespace vt::ui {
namespace {

constexpr const char* kIniType = "VTouchingPanel";
// At the 13 px font; they grow with it (the text scales with the window).
constexpr float kMargin_px = 8.0f;
constexpr float kGap_px = 4.0f;


struct PanelState {
  bool docked = true;
  ImVec2 placed{-1.0f, -1.0f};  // where the panel was docked last frame
};

struct LayoutState {
  std::map<std::string, PanelState> panels;  // by ImGui window id text; nodes stay put
  int frame = -1;
  std::array<float, 3> offset_px{};  // per corner, how far this frame's docked panels reach
  PanelState* current = nullptr;
  DockCorner currentCorner = DockCorner::TopLeft;
};

// One ImGui context per process (ImGuiLayer enforces it), so the layout is process state too.
LayoutState& state() {
  static LayoutState s;
  return s;
}

// The part of a title ImGui identifies the window by ("Devices  60 fps###Devices" -> "###Devices").
std::string windowId(const char* name) {
  const char* id = std::strstr(name, "###");
  return id ? id : name;
}

void* readOpen(ImGuiContext*, ImGuiSettingsHandler*, const char* name) { return &state().panels[name]; }

void readLine(ImGuiContext*, ImGuiSettingsHandler*, void* entry, const char* line) {
  int docked = 1;
  if (std::sscanf(line, "docked=%d", &docked) == 1) static_cast<PanelState*>(entry)->docked = docked != 0;
}

void writeAll(ImGuiContext*, ImGuiSettingsHandler* handler, ImGuiTextBuffer* out) {
  for (const auto& [name, panel] : state().panels) out->appendf("[%s][%s]\ndocked=%d\n\n", handler->TypeName, name.c_str(), int(panel.docked));
}

void clearAll(ImGuiContext*, ImGuiSettingsHandler*) {
  for (auto& [name, panel] : state().panels) panel.docked = true;
}

}  // namespace

void installHudLayout() {
  // Headset mode without a mirror window has no ImGui context: nothing to lay out.
  if (ImGui::GetCurrentContext() == nullptr || ImGui::FindSettingsHandler(kIniType)) return;
  state().panels.clear();
  state().current = nullptr;
  ImGuiSettingsHandler handler;
  handler.TypeName = kIniType;
  handler.TypeHash = ImHashStr(kIniType);
  handler.ClearAllFn = clearAll;
  handler.ReadOpenFn = readOpen;
  handler.ReadLineFn = readLine;
  handler.WriteAllFn = writeAll;
  ImGui::GetCurrentContext()->SettingsHandlers.push_back(handler);
}

void dockNextPanel(const char* name, DockCorner corner, bool collapsed) {
  LayoutState& s = state();
  if (s.frame != ImGui::GetFrameCount()) s.frame = ImGui::GetFrameCount(), s.offset_px = {};
  const std::string id = windowId(name);
  PanelState& panel = s.panels[id];
  s.current = &panel;
  s.currentCorner = corner;
  // The user dragged a docked panel by its title: it stays where it is dropped from now on.
  const ImGuiWindow* window = ImGui::FindWindowByName(id.c_str());
  const ImGuiWindow* moving = ImGui::GetCurrentContext()->MovingWindow;
  if (panel.docked && window && moving && moving->RootWindow == window &&
      (window->Pos.x != panel.placed.x || window->Pos.y != panel.placed.y)) {
    panel.docked = false;
    ImGui::MarkIniSettingsDirty();
  }
  if (panel.docked) {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const float offset = s.offset_px[std::size_t(corner)];
    const float margin = kMargin_px * hudScale();
    switch (corner) {
      case DockCorner::TopLeft: ImGui::SetNextWindowPos({margin, margin + offset}, ImGuiCond_Always); break;
      case DockCorner::TopRight:
        ImGui::SetNextWindowPos({display.x - margin, margin + offset}, ImGuiCond_Always, {1.0f, 0.0f});
        break;
      case DockCorner::BottomRight:
        ImGui::SetNextWindowPos({display.x - margin, display.y - margin - offset}, ImGuiCond_Always, {1.0f, 1.0f});
        break;
    }
  }
  if (collapsed) ImGui::SetNextWindowCollapsed(true, ImGuiCond_FirstUseEver);
}

void endDockedPanel() {
  LayoutState& s = state();
  if (!s.current) return;
  if (s.current->docked) {
    s.offset_px[std::size_t(s.currentCorner)] += ImGui::GetWindowSize().y + kGap_px * hudScale();
    s.current->placed = ImGui::GetWindowPos();
  }
  s.current = nullptr;
}

float hudScale() { return ImGui::GetFontSize() / 13.0f; }

void dockAllPanels() {
  for (auto& [name, panel] : state().panels) panel.docked = true;
  ImGui::MarkIniSettingsDirty();
}

}  // namespace vt::ui
