#include "modes/touch_hud.hpp"

#include <cstdlib>
#include <filesystem>
#include <vector>

#include "modes/hand_control.hpp"
#include "ui/hud_layout.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/log.hpp"
#include "vt/core/realtime.hpp"

namespace vt::app {

std::string hudSettingsFile() {
  namespace fs = std::filesystem;
  fs::path dir;
  if (const char* xdg = std::getenv("XDG_CONFIG_HOME"); xdg && *xdg) {
    dir = fs::path(xdg) / "vtouching";
  } else if (const char* home = std::getenv("HOME"); home && *home) {
    dir = fs::path(home) / ".config" / "vtouching";
  } else {
    log::info("HUD layout not kept: neither XDG_CONFIG_HOME nor HOME is set");
    return {};
  }
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) {
    log::info("HUD layout not kept: ", dir.string(), ": ", ec.message());
    return {};
  }
  return (dir / "imgui.ini").string();
}

TouchHud::TouchHud(const LoadedScene& scene, const HapticOptions& options, bool remote, ui::HudStatus status,
                       bool desktopControls)
    : m_scene(scene), m_status(std::move(status)), m_desktopControls(desktopControls) {
  m_settings.help = desktopControls;
  m_settings.haptic = options;
  m_settings.editable = !remote;
  m_status.remote = remote;
  ui::installHudLayout();
}

void TouchHud::draw(TouchPipeline& haptics, double frame_ms, bool panels) {
  if (!panels) {
    if (m_desktopControls) ui::drawHelpOverlay();
    return;
  }
  m_status.frame_ms = frame_ms;
  m_status.hapticRate_hz = haptics.measuredRate_hz();
  m_status.loop = haptics.stats();
  const std::int64_t now_ns = SteadyClock::instance().now_ns();
  m_status.overrunRate_hz = m_overruns.update(now_ns, m_status.loop.overruns);
  m_status.stalePoseRate_hz = m_stalePoses.update(now_ns, m_status.loop.stalePoses);
  m_status.glove = haptics.gloveStatus();
  m_status.realtime = describeRealtimeGrants();
  m_status.outputs = haptics.outputsStatus();
  m_status.network = haptics.networkStatus();
  m_status.droppedRecords = haptics.droppedRecords();
  m_status.timing = haptics.timingStatus();
  m_status.consistency = haptics.consistencyStatus();
  std::vector<ui::HudContact> contacts;
  for (std::size_t c = 0; c < haptics.contacts().size(); ++c) {
    const ContactView& view = haptics.contacts()[c];
    const haptics::ContactTrace& t = view.last;
    ui::HudContact line;
    line.finger = fingerOfTip(haptics.config().contacts[c].joint);
    line.inContact = t.inContact;
    line.material = t.inContact && t.material >= 0 ? m_scene.scene->materials[std::size_t(t.material)].name : "";
    line.u = t.u, line.v = t.v, line.depth_m = t.depth_m, line.intensity = t.intensity;
    if (t.inContact && t.material >= 0 && m_scene.scene->materials[std::size_t(t.material)].vibrationMapAcross >= 0) {
      line.acrossWeight = t.acrossWeight;
    }
    line.history = &view.history;
    contacts.push_back(std::move(line));
  }
  if (ui::drawHud(m_status, contacts, haptics.gloveLevels(), m_settings)) haptics.setOptions(m_settings.haptic);
}

}  // namespace vt::app
