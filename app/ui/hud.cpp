#include "ui/hud.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "ui/touch_figure.hpp"

namespace vt::ui {
namespace {

ImU32 toImColor(glm::u8vec4 c) { return IM_COL32(c.r, c.g, c.b, c.a); }

void touchPanel(const std::vector<HudContact>& contacts) {
  ImGui::SetNextWindowPos({10, 10}, ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize({340, 0}, ImGuiCond_FirstUseEver);
  ImGui::Begin("Touch");
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const HudContact& c = contacts[i];
    static const char* names[] = {"thumb", "index", "middle", "ring", "little"};
    const glm::u8vec4 color = fingerColor(c.finger);
    ImGui::PushStyleColor(ImGuiCol_Text, toImColor(color));
    ImGui::Text("%-7s", names[std::clamp(c.finger, 0, 4)]);
    ImGui::PopStyleColor();
    ImGui::SameLine();
    if (c.inContact && c.material.empty()) {  // client mode: the server found the contact
      ImGui::Text("level %.2f (from the server)", double(c.intensity));
    } else if (c.inContact) {
      ImGui::Text("%s  uv %.3f %.3f  %.1f mm  %.2f", c.material.c_str(), double(c.u), double(c.v),
                  double(c.depth_m * 1000.0f), double(c.intensity));
    } else {
      ImGui::TextDisabled("no contact");
    }
    if (c.history) {
      ImGui::PushID(int(i));
      ImGui::PushStyleColor(ImGuiCol_PlotLines, toImColor(color));
      ImGui::PlotLines("##plot", c.history->data(), int(c.history->size()), 0, nullptr, 0.0f, 0.8f, {320, 28});
      ImGui::PopStyleColor();
      ImGui::PopID();
    }
  }
  ImGui::End();
}

bool settingsPanel(HudSettings& s) {
  bool changed = false;
  ImGui::Begin("Settings");
  if (!s.editable) ImGui::TextWrapped("client mode: the tactile settings are the server's (vtouching serve options)");
  ImGui::BeginDisabled(!s.editable);
  app::HapticOptions& h = s.haptic;
  const char* models[] = {"paper intensity", "texture waveform", "taxel waveform"};
  if (int model = int(h.model); ImGui::Combo("tactile model", &model, models, 3)) {
    h.model = haptics::TactileModel(model);
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
  ImGui::EndDisabled();
  ImGui::Checkbox("vibration-map overlay", &s.overlay);
  ImGui::Checkbox("controls help", &s.help);
  ImGui::End();
  return changed;
}

void statusPanel(const HudStatus& st) {
  ImGui::Begin("Devices");
  ImGui::Text("frame %.1f ms (%.0f fps)   %s %.0f Hz", st.frame_ms, st.frame_ms > 0 ? 1000.0 / st.frame_ms : 0.0,
              st.remote ? "tactile stream" : "haptic", st.hapticRate_hz);
  if (!st.remote) {  // in client mode the loop runs on the server
    ImGui::Text("haptic tick p50 %.0f us p99 %.0f us, jitter p99 %.0f us", st.loop.tickP50_us, st.loop.tickP99_us,
                st.loop.jitterP99_us);
    ImGui::Text("overruns %llu  stale poses %llu", static_cast<unsigned long long>(st.loop.overruns),
                static_cast<unsigned long long>(st.loop.stalePoses));
  }
  if (!st.timing.empty()) ImGui::TextWrapped("hand: %s", st.timing.c_str());
  ImGui::Separator();
  ImGui::TextWrapped("scene: %s", st.scene.c_str());
  ImGui::TextWrapped("Vulkan: %s", st.vulkanDevice.c_str());
  ImGui::TextWrapped("OpenXR: %s", st.xrRuntime.c_str());
  ImGui::TextWrapped("glove: %s", st.glove.c_str());
  if (!st.outputs.empty()) ImGui::TextWrapped("outputs: %s", st.outputs.c_str());
  ImGui::TextWrapped("real time: %s", st.realtime.c_str());
  ImGui::TextWrapped("network: %s", st.network.c_str());
  if (!st.recording.empty()) {
    ImGui::TextWrapped("recording: %s (%llu dropped)", st.recording.c_str(),
                       static_cast<unsigned long long>(st.droppedRecords));
  }
  ImGui::End();
}

// Actuators on a right-hand outline, palm towards the viewer: fingertips on top, palm pads below.
void glovePanel(const std::array<float, haptics::kMaxActuators>& levels) {
  ImGui::Begin("Glove");
  const ImVec2 o = ImGui::GetCursorScreenPos();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 spots[haptics::kMaxActuators] = {
      {20, 95},  {50, 22},  {80, 12}, {110, 20}, {136, 42},  // thumb, index, middle, ring, pinky tips
      {55, 80},  {55, 120}, {85, 80}, {115, 80}, {115, 120}};  // palm pads
  draw->AddRectFilled({o.x + 38, o.y + 62}, {o.x + 132, o.y + 150}, IM_COL32(90, 80, 75, 255), 12.0f);
  for (int f = 1; f < 5; ++f) draw->AddLine({o.x + spots[f].x, o.y + spots[f].y}, {o.x + spots[f].x, o.y + 66}, IM_COL32(90, 80, 75, 255), 14.0f);
  draw->AddLine({o.x + spots[0].x, o.y + spots[0].y}, {o.x + 45, o.y + 125}, IM_COL32(90, 80, 75, 255), 14.0f);
  for (int a = 0; a < haptics::kMaxActuators; ++a) {
    const float level = std::sqrt(std::clamp(levels[std::size_t(a)], 0.0f, 1.0f));  // weak levels stay visible
    const ImVec2 c{o.x + spots[a].x, o.y + spots[a].y};
    draw->AddCircleFilled(c, 9.0f, IM_COL32(int(40 + 215 * level), int(40 + 120 * level), 40, 255));
    draw->AddCircle(c, 9.0f, IM_COL32(230, 230, 230, 255));
  }
  ImGui::Dummy({160, 160});
  float strongest = 0.0f;
  for (float level : levels) strongest = std::max(strongest, level);
  ImGui::Text("strongest actuator %.2f", double(strongest));
  ImGui::End();
}

}  // namespace

bool drawHud(const HudStatus& status, const std::vector<HudContact>& contacts,
             const std::array<float, haptics::kMaxActuators>& gloveLevels, HudSettings& settings) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  touchPanel(contacts);
  // Right column: devices on top, settings, the glove at the bottom (first use; the user may move them).
  const float x = display.x - 370;
  ImGui::SetNextWindowPos({x, 10}, ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize({360, 285}, ImGuiCond_FirstUseEver);
  statusPanel(status);
  ImGui::SetNextWindowPos({x, 305}, ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize({360, 0}, ImGuiCond_FirstUseEver);
  const bool changed = settingsPanel(settings);
  ImGui::SetNextWindowPos({x, display.y - 10}, ImGuiCond_FirstUseEver, {0.0f, 1.0f});
  ImGui::SetNextWindowSize({190, 0}, ImGuiCond_FirstUseEver);
  glovePanel(gloveLevels);
  if (settings.help) drawHelpOverlay();
  return changed;
}

void drawHelpOverlay() {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos({10, display.y - 10}, ImGuiCond_Always, {0.0f, 1.0f});
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

}  // namespace vt::ui
