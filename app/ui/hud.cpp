#include "ui/hud.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <imgui.h>

#include "modes/hand_control.hpp"
#include "ui/hud_layout.hpp"
#include "ui/touch_figure.hpp"

namespace vt::ui {
namespace {

ImU32 toImColor(glm::u8vec4 c) { return IM_COL32(c.r, c.g, c.b, c.a); }

// A size laid out for the 13 px font, at the font in use.
float px(float size) { return size * hudScale(); }
ImVec2 px(float x, float y) { return {px(x), px(y)}; }

// A measured rate in a fixed width ("  60 Hz", " 995 Hz", "  -- Hz"): the line around it keeps
// its length as the figure changes.
std::string fixedRateText(double rate_hz) {
  char text[32];
  if (std::isnan(rate_hz)) std::snprintf(text, sizeof text, "%4s Hz", "--");
  else std::snprintf(text, sizeof text, "%4.0f Hz", rate_hz);
  return text;
}

// Wrapped text whose block never gets shorter than the tallest it has been in this window: a
// line whose figures change length may wrap once more or less, and the panels stacked below
// must not jump (the click aimed at a header would miss). ImGui's per-window storage keeps it.
void steadyWrapped(const char* label, const std::string& text) {
  const float top = ImGui::GetCursorPosY();
  ImGui::TextWrapped("%s %s", label, text.c_str());
  float& tallest = *ImGui::GetStateStorage()->GetFloatRef(ImGui::GetID(label), 0.0f);
  const float height = ImGui::GetCursorPosY() - top;
  if (height < tallest) ImGui::Dummy({0.0f, tallest - height - ImGui::GetStyle().ItemSpacing.y});
  tallest = std::max(tallest, height);
}

// `text` cut short with "..." to fit `width_px` (whole when it fits; never inside a UTF-8 character).
std::string elided(const std::string& text, float width_px) {
  if (ImGui::CalcTextSize(text.c_str()).x <= width_px) return text;
  const float dots_px = ImGui::CalcTextSize("...").x;
  const auto insideCharacter = [&](std::size_t n) { return n < text.size() && (text[n] & 0xC0) == 0x80; };
  std::size_t n = text.size();
  while (n > 0 && (insideCharacter(n) || ImGui::CalcTextSize(text.c_str(), text.c_str() + n).x + dots_px > width_px)) --n;
  return text.substr(0, n) + "...";
}

// One row per contact: finger, material (elided, full name and uv in a tooltip), depth and
// intensity in fixed columns so a long material name never hides the figures; its plot below.
// Rows and plots are packed tight so the panel stays above the scene's top-left plates.
void touchPanel(const std::vector<HudContact>& contacts) {
  dockNextPanel("Touch", DockCorner::TopLeft);
  ImGui::SetNextWindowSize({px(330), 0}, ImGuiCond_FirstUseEver);
  ImGui::Begin("Touch");
  endDockedPanel();
  ImGui::PushStyleVar(ImGuiStyleVar_ItemSpacing, {ImGui::GetStyle().ItemSpacing.x, 1.0f});
  ImGui::PushStyleVar(ImGuiStyleVar_CellPadding, {ImGui::GetStyle().CellPadding.x, 1.0f});
  // One small table per line (the plot goes between them, across the panel's width).
  const ImGuiTableFlags flags = ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_NoPadOuterX;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const HudContact& c = contacts[i];
    const glm::u8vec4 color = fingerColor(c.finger);
    ImGui::PushID(int(i));
    if (ImGui::BeginTable("line", 4, flags)) {
      ImGui::TableSetupColumn("finger", ImGuiTableColumnFlags_WidthFixed, ImGui::CalcTextSize("middle").x);
      ImGui::TableSetupColumn("material", ImGuiTableColumnFlags_WidthStretch);
      ImGui::TableSetupColumn("depth", ImGuiTableColumnFlags_WidthFixed, ImGui::CalcTextSize("00.0 mm").x);
      ImGui::TableSetupColumn("level", ImGuiTableColumnFlags_WidthFixed, ImGui::CalcTextSize("0.00").x);
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::PushStyleColor(ImGuiCol_Text, toImColor(color));
      ImGui::TextUnformatted(app::fingerName(c.finger));
      ImGui::PopStyleColor();
      ImGui::TableNextColumn();
      if (c.inContact && c.material.empty()) {  // client mode: the server found the contact
        ImGui::TextUnformatted("(server)");
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("the contact was found on the server; this is its actuator level");
      } else if (c.inContact) {
        char direction[32] = "";  // scanned in two directions: which map the finger's motion picks
        if (c.acrossWeight >= 0.0f) {
          std::snprintf(direction, sizeof direction, "%s %.0f%%", c.acrossWeight > 0.5f ? "across" : "along",
                        double(100.0f * std::max(c.acrossWeight, 1.0f - c.acrossWeight)));
        }
        const float directionWidth = direction[0] ? ImGui::CalcTextSize(direction).x + ImGui::GetStyle().ItemSpacing.x : 0.0f;
        ImGui::TextUnformatted(elided(c.material, ImGui::GetContentRegionAvail().x - directionWidth).c_str());
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s\nuv %.3f %.3f", c.material.c_str(), double(c.u), double(c.v));
        if (direction[0]) {
          ImGui::SameLine();
          ImGui::TextUnformatted(direction);
        }
        ImGui::TableNextColumn();
        ImGui::Text("%4.1f mm", double(c.depth_m * 1000.0f));
      } else {
        ImGui::TextDisabled("no contact");
      }
      ImGui::TableSetColumnIndex(3);
      if (c.inContact) ImGui::Text("%.2f", double(c.intensity));
      ImGui::EndTable();
    }
    if (c.history) {
      ImGui::PushStyleColor(ImGuiCol_PlotLines, toImColor(color));
      ImGui::PlotLines("##plot", c.history->data(), int(c.history->size()), 0, nullptr, 0.0f, 0.8f,
                       {ImGui::GetContentRegionAvail().x, px(16)});
      ImGui::PopStyleColor();
    }
    ImGui::PopID();
  }
  ImGui::PopStyleVar(2);
  ImGui::End();
}

bool settingsPanel(HudSettings& s) {
  bool changed = false;
  char title[96];
  static const char* models[] = {"paper intensity", "texture waveform", "taxel waveform"};
  std::snprintf(title, sizeof title, "Settings  %s, gain %.2f###Settings", models[std::clamp(int(s.haptic.model), 0, 2)],
                double(s.haptic.gain));
  dockNextPanel(title, DockCorner::TopRight, true);
  ImGui::Begin(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  endDockedPanel();
  if (!s.editable) ImGui::TextUnformatted("client mode: the tactile settings are\nthe server's (vtouching serve options)");
  ImGui::BeginDisabled(!s.editable);
  app::HapticOptions& h = s.haptic;
  ImGui::PushItemWidth(px(200));
  if (int model = int(h.model); ImGui::Combo("tactile model", &model, models, 3)) {
    h.model = haptics::TactileModelKind(model);
    changed = true;
  }
  ImGui::SliderFloat("gain", &h.gain, 0.0f, 2.0f, "%.2f");
  changed |= ImGui::IsItemDeactivatedAfterEdit();  // restart the loop once, on release
  int rateIndex = int(std::find(kRates.begin(), kRates.end(), int(h.rate_hz)) - kRates.begin());
  const char* rates[] = {"250 Hz", "500 Hz", "1000 Hz", "2000 Hz"};
  if (ImGui::Combo("haptic rate", &rateIndex, rates, int(kRates.size()))) {
    h.rate_hz = float(kRates[std::size_t(rateIndex)]);
    changed = true;
  }
  const char* presets[] = {"five fingertips", "V-Touching glove (index, middle, ring)"};
  if (int preset = int(h.preset); ImGui::Combo("mapping", &preset, presets, 2)) {
    h.preset = app::MappingPreset(preset);
    changed = true;
  }
  const char* samplings[] = {"latest pose", "interpolate (delayed)", "predict (default)"};
  if (int sampling = int(h.sampling); ImGui::Combo("hand timing", &sampling, samplings, 3)) {
    h.sampling = PoseSampling(sampling);
    changed = true;
  }
  ImGui::PopItemWidth();
  ImGui::EndDisabled();
  ImGui::Checkbox("vibration-map overlay", &s.overlay);
  ImGui::Checkbox("controls help", &s.help);
  if (ImGui::Button("dock panels")) dockAllPanels();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("put every panel back at the window's edges");
  ImGui::End();
  return changed;
}

// Every figure in a fixed width, and wrapped lines that never shrink (steadyWrapped): the panel
// keeps its size as its numbers change, so the panels stacked below it stay put.
void statusPanel(const HudStatus& st, float poseTimeout_ms) {
  const double fps = st.frame_ms > 0 ? 1000.0 / st.frame_ms : 0.0;
  const std::string rate = fixedRateText(st.hapticRate_hz);
  char title[96];
  std::snprintf(title, sizeof title, "Devices %5.0f fps  %s %s###Devices", fps, st.remote ? "stream" : "haptic", rate.c_str());
  dockNextPanel(title, DockCorner::TopRight, true);
  ImGui::SetNextWindowSize({px(360), 0}, ImGuiCond_FirstUseEver);
  ImGui::Begin(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  endDockedPanel();
  ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + px(340));
  ImGui::Text("frame %6.1f ms (%5.0f fps)  %s %s", st.frame_ms, fps, st.remote ? "tactile stream" : "haptic", rate.c_str());
  if (!st.remote) {  // in client mode the loop runs on the server
    ImGui::Text("haptic tick p50 %5.0f us p99 %5.0f us, jitter p99 %5.0f us", st.loop.tickP50_us, st.loop.tickP99_us,
                st.loop.jitterP99_us);
    // Rates over the last seconds: an old burst (start-up, a dropped frame) does not stay on show.
    ImGui::Text("overruns %6.1f/s", st.overrunRate_hz);
    if (ImGui::IsItemHovered()) {
      ImGui::SetTooltip("haptic ticks that started a whole period late (the thread was not\nscheduled in time), "
                        "per second over the last 5 s\n%llu since the loop started",
                        static_cast<unsigned long long>(st.loop.overruns));
    }
    ImGui::SameLine();
    ImGui::Text("  stale poses %6.1f/s (?)", st.stalePoseRate_hz);
    if (ImGui::IsItemHovered()) {
      ImGui::SetTooltip(
          "stale poses: haptic ticks that found no valid hand pose, the newest\n"
          "one being older than the pose timeout (%.0f ms) or marked invalid,\n"
          "per second over the last 5 s (%llu since the loop started).\n"
          "Causes: hand tracking lost or the hand out of view, no pose yet,\n"
          "poses arriving late (a stalled frame, a slow or lossy network).\n"
          "On such a tick the hand counts as gone: no contact, and the\n"
          "actuators stay silent until a fresh pose arrives.",
          double(poseTimeout_ms), static_cast<unsigned long long>(st.loop.stalePoses));
    }
  }
  if (!st.timing.empty()) steadyWrapped("hand:", st.timing);
  if (!st.consistency.empty()) steadyWrapped("consistency:", st.consistency);
  ImGui::Separator();
  steadyWrapped("scene:", st.scene);
  steadyWrapped("Vulkan:", st.vulkanDevice);
  steadyWrapped("OpenXR:", st.xrRuntime);
  steadyWrapped("glove:", st.glove);
  if (!st.outputs.empty()) steadyWrapped("outputs:", st.outputs);
  steadyWrapped("real time:", st.realtime);
  steadyWrapped("network:", st.network);
  if (!st.recording.empty()) {
    char dropped[48];
    std::snprintf(dropped, sizeof dropped, " (%8llu dropped)", static_cast<unsigned long long>(st.droppedRecords));
    steadyWrapped("recording:", st.recording + dropped);
  }
  ImGui::PopTextWrapPos();
  ImGui::End();
}

// Actuators on a right-hand outline, palm towards the viewer: fingertips on top, palm pads below.
void glovePanel(const std::array<float, haptics::kMaxActuators>& levels) {
  float strongest = 0.0f;
  for (float level : levels) strongest = std::max(strongest, level);
  char title[64];
  std::snprintf(title, sizeof title, "Glove  strongest %4.2f###Glove", double(strongest));
  dockNextPanel(title, DockCorner::TopRight, true);
  ImGui::Begin(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  endDockedPanel();
  const ImVec2 o = ImGui::GetCursorScreenPos();
  const float s = hudScale();
  const auto at = [&](float x, float y) { return ImVec2{o.x + s * x, o.y + s * y}; };
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 spots[haptics::kMaxActuators] = {
      {20, 95},  {50, 22},  {80, 12}, {110, 20}, {136, 42},  // thumb, index, middle, ring, little tips
      {55, 80},  {55, 120}, {85, 80}, {115, 80}, {115, 120}};  // palm pads
  draw->AddRectFilled(at(38, 62), at(132, 150), IM_COL32(90, 80, 75, 255), s * 12.0f);
  for (int f = 1; f < 5; ++f) draw->AddLine(at(spots[f].x, spots[f].y), at(spots[f].x, 66), IM_COL32(90, 80, 75, 255), s * 14.0f);
  draw->AddLine(at(spots[0].x, spots[0].y), at(45, 125), IM_COL32(90, 80, 75, 255), s * 14.0f);
  for (int a = 0; a < haptics::kMaxActuators; ++a) {
    const float level = std::sqrt(std::clamp(levels[std::size_t(a)], 0.0f, 1.0f));  // weak levels stay visible
    const ImVec2 c = at(spots[a].x, spots[a].y);
    draw->AddCircleFilled(c, s * 9.0f, IM_COL32(int(40 + 215 * level), int(40 + 120 * level), 40, 255));
    draw->AddCircle(c, s * 9.0f, IM_COL32(230, 230, 230, 255));
  }
  ImGui::Dummy(px(160, 160));
  ImGui::End();
}

// The overlay's colour scale, docked bottom-right while the overlay is on. The colours are
// shaders/overlay.frag's heat(): black -> red -> yellow -> white over the map's 0..1.
void colourBarPanel() {
  dockNextPanel("Vibration map", DockCorner::BottomRight);
  ImGui::Begin("Vibration map", nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoFocusOnAppearing);
  endDockedPanel();
  auto heat = [](float t) {
    const auto channel = [](float v) { return int(std::lround(255.0f * std::clamp(v, 0.0f, 1.0f))); };
    return IM_COL32(channel(3.0f * t), channel(3.0f * t - 1.0f), channel(3.0f * t - 2.0f), 255);
  };
  const ImVec2 o = ImGui::GetCursorScreenPos();
  const float width = px(160), height = px(14);
  constexpr int kSteps = 3;  // heat() is linear between its thirds
  ImDrawList* draw = ImGui::GetWindowDrawList();
  for (int i = 0; i < kSteps; ++i) {
    const float t0 = float(i) / kSteps, t1 = float(i + 1) / kSteps;
    draw->AddRectFilledMultiColor({o.x + width * t0, o.y}, {o.x + width * t1, o.y + height}, heat(t0), heat(t1), heat(t1),
                                  heat(t0));
  }
  draw->AddRect(o, {o.x + width, o.y + height}, IM_COL32(200, 200, 200, 255));
  ImGui::Dummy({width, height});
  ImGui::Text("0");
  ImGui::SameLine(width - ImGui::CalcTextSize("map maximum").x + ImGui::GetStyle().WindowPadding.x);
  ImGui::Text("map maximum");
  ImGui::End();
}

}  // namespace

bool drawHud(const HudStatus& status, const std::vector<HudContact>& contacts,
             const std::array<float, haptics::kMaxActuators>& gloveLevels, HudSettings& settings) {
  // Touch on the left; on the right, collapsed to their title line until opened: devices,
  // settings, the glove (each title carries its key figure).
  touchPanel(contacts);
  statusPanel(status, settings.haptic.poseTimeout_ms);
  const bool changed = settingsPanel(settings);
  glovePanel(gloveLevels);
  if (settings.overlay) colourBarPanel();
  if (settings.help) drawHelpOverlay();
  return changed;
}

void drawHelpOverlay() {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos({px(10), display.y - px(10)}, ImGuiCond_Always, {0.0f, 1.0f});
  ImGui::SetNextWindowBgAlpha(0.55f);
  ImGui::Begin("Controls", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoFocusOnAppearing |
                   ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs);
  ImGui::TextUnformatted(
      "mouse: move the hand over the surfaces\n"
      "left button / scroll: press into the surface\n"
      "W A S D: move the hand   arrows: up/down, turn\n"
      "1-5: curl thumb..little   Q: reset the hand\n"
      "right-drag: orbit the camera   Esc: quit");
  ImGui::End();
}

std::string rateText(double rate_hz) {
  if (std::isnan(rate_hz)) return "-- Hz";
  char text[32];
  std::snprintf(text, sizeof text, "%.0f Hz", rate_hz);
  return text;
}

}  // namespace vt::ui
