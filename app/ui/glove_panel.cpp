#include "ui/glove_panel.hpp"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <string>

namespace vt::app {
namespace {

using haptics::ActuatorId;

// Actuator positions on a right hand seen from the palm (thumb on the right), in a unit box.
const std::array<ImVec2, haptics::kMaxActuators> kActuatorAt = {{
    {0.90f, 0.40f},  // thumb
    {0.70f, 0.08f},  // index
    {0.52f, 0.03f},  // middle
    {0.35f, 0.07f},  // ring
    {0.18f, 0.20f},  // pinky
    {0.68f, 0.52f},  // palm-index-up
    {0.68f, 0.80f},  // palm-index-down
    {0.50f, 0.52f},  // palm-middle-up
    {0.26f, 0.55f},  // palm-pinky-up
    {0.26f, 0.82f},  // palm-pinky-down
}};
// Where each finger leaves the palm (thumb, index, middle, ring, pinky).
const std::array<ImVec2, 5> kFingerBase = {{{0.76f, 0.70f}, {0.68f, 0.45f}, {0.51f, 0.44f}, {0.35f, 0.45f}, {0.20f, 0.48f}}};

ImU32 levelColour(float level) {
  const float t = std::clamp(level, 0.0f, 1.0f);
  // Dark grey when idle, through orange to yellow at full drive.
  return IM_COL32(int(60 + 195 * t), int(60 + 140 * t), int(60 - 40 * t), 255);
}

void drawHand(const haptics::ActuatorFrame& frame) {
  const float width = std::max(160.0f, std::min(ImGui::GetContentRegionAvail().x, 320.0f));
  const float height = width * 1.1f;
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const auto at = [&](ImVec2 p) { return ImVec2(origin.x + p.x * width, origin.y + p.y * height); };
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImU32 skin = IM_COL32(120, 110, 100, 255);
  draw->AddRectFilled(at({0.12f, 0.42f}), at({0.80f, 0.97f}), skin, width * 0.08f);
  for (std::size_t f = 0; f < kFingerBase.size(); ++f) {
    draw->AddLine(at(kFingerBase[f]), at(kActuatorAt[f]), skin, width * 0.1f);
  }
  const float radius = width * 0.045f;
  for (int i = 0; i < haptics::kMaxActuators; ++i) {
    const bool used = i < frame.actuatorCount;
    const float level = used ? frame.intensity[std::size_t(i)] : 0.0f;
    const ImVec2 centre = at(kActuatorAt[std::size_t(i)]);
    draw->AddCircleFilled(centre, radius * (1.0f + 0.5f * std::clamp(level, 0.0f, 1.0f)), levelColour(level));
    draw->AddCircle(centre, radius, used ? IM_COL32(230, 230, 230, 255) : IM_COL32(90, 90, 90, 255));
  }
  ImGui::Dummy(ImVec2(width, height));
  // Hovering an actuator names it with its level and frequency.
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  for (int i = 0; i < haptics::kMaxActuators; ++i) {
    const ImVec2 c = at(kActuatorAt[std::size_t(i)]);
    const float dx = mouse.x - c.x, dy = mouse.y - c.y;
    if (dx * dx + dy * dy <= radius * radius * 2.25f) {
      const std::string name(haptics::actuatorName(ActuatorId(i)));
      ImGui::SetTooltip("%s: %.2f at %.0f Hz", name.c_str(), double(frame.intensity[std::size_t(i)]),
                        double(frame.frequency_hz[std::size_t(i)]));
    }
  }
}

void drawStatus(const haptics::glove::GloveStatus& status) {
  if (status.connected) {
    ImGui::TextColored(ImVec4(0.4f, 0.9f, 0.4f, 1.0f), "connected  %s  serial %s", status.path.c_str(), status.info.serial.data());
  } else {
    ImGui::TextColored(ImVec4(0.9f, 0.6f, 0.3f, 1.0f), "not connected");
  }
  ImGui::Text("rate %.0f Hz   sent %llu   dropped %llu", status.sendRate_hz,
              static_cast<unsigned long long>(status.reportsSent), static_cast<unsigned long long>(status.framesDropped));
  ImGui::Text("write errors %llu   connects %llu", static_cast<unsigned long long>(status.writeErrors),
              static_cast<unsigned long long>(status.connects));
  ImGui::Text("input reports %llu   rejected %llu", static_cast<unsigned long long>(status.inputReports),
              static_cast<unsigned long long>(status.inputRejected));
  if (status.failsafe != haptics::FailsafeReason::None) {
    const std::string reason(haptics::failsafeReasonName(status.failsafe));
    ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.2f, 1.0f), "failsafe: silent (%s)", reason.c_str());
  }
  if (!status.lastError.empty()) ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.4f, 1.0f), "%s", status.lastError.c_str());
}

void drawSimulated(haptics::glove::SimulatedGlove& glove) {
  ImGui::Separator();
  ImGui::Text("simulated glove%s", glove.silenced() ? ": silenced by keep-alive" : "");
  static constexpr const char* kFingers[kFingerCount] = {"thumb", "index", "middle", "ring", "little"};
  FingerCurls curls = glove.flexion();
  bool changed = false;
  for (std::size_t f = 0; f < curls.size(); ++f) changed |= ImGui::SliderFloat(kFingers[f], &curls[f], 0.0f, 1.0f);
  if (changed) glove.setFlexion(curls);
}

}  // namespace

void drawGlovePanel(const haptics::ActuatorFrame& frame, const haptics::glove::GloveStatus& status,
                    haptics::glove::SimulatedGlove* simulated) {
  if (!ImGui::Begin("Glove")) {
    ImGui::End();
    return;
  }
  drawHand(frame);
  drawStatus(status);
  if (simulated) drawSimulated(*simulated);
  ImGui::End();
}

}  // namespace vt::app
