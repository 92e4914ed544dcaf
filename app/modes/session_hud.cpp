#include "modes/session_hud.hpp"

#include <vector>

#include "modes/hand_control.hpp"

namespace vt::app {

SessionHud::SessionHud(const LoadedScene& scene, const HapticOptions& options, bool remote, ui::HudStatus status,
                       bool desktopControls)
    : m_scene(scene), m_status(std::move(status)), m_desktopControls(desktopControls) {
  m_settings.help = desktopControls;
  m_settings.model = int(options.model);
  m_settings.gain = options.gain;
  m_settings.rate_hz = int(options.rate_hz);
  m_settings.preset = int(options.preset);
  m_settings.editable = !remote;
  m_status.remote = remote;
}

void SessionHud::draw(HapticSession& haptics, double frame_ms, bool panels) {
  if (!panels) {
    if (m_desktopControls) ui::drawHelpOverlay();
    return;
  }
  m_status.frame_ms = frame_ms;
  m_status.hapticRate_hz = haptics.measuredRate_hz();
  m_status.loop = haptics.stats();
  m_status.glove = haptics.gloveStatus();
  m_status.network = haptics.networkStatus();
  m_status.droppedRecords = haptics.droppedFrames();
  std::vector<ui::HudContact> contacts;
  for (std::size_t c = 0; c < haptics.contacts().size(); ++c) {
    const ContactView& view = haptics.contacts()[c];
    const haptics::ContactTrace& t = view.last;
    ui::HudContact line;
    line.finger = fingerOfTip(haptics.config().contacts[c].joint);
    line.inContact = t.inContact;
    line.material = t.inContact && t.material >= 0 ? m_scene.scene->materials[std::size_t(t.material)].name : "";
    line.u = t.u, line.v = t.v, line.depth_m = t.depth_m, line.intensity = t.intensity;
    line.history = &view.history;
    contacts.push_back(std::move(line));
  }
  if (ui::drawHud(m_status, contacts, haptics.gloveLevels(), m_settings)) {
    HapticOptions changed = haptics.options();
    changed.model = haptics::TactileModel(m_settings.model);
    changed.gain = m_settings.gain;
    changed.rate_hz = float(m_settings.rate_hz);
    changed.preset = MappingPreset(m_settings.preset);
    haptics.setOptions(changed);
  }
}

}  // namespace vt::app
