#include "modes/contact_markers.hpp"

#include <algorithm>

namespace vt::app {
namespace {

/// How far from the drawn joint's sphere a surface still gets the ring: the drawn hand can lag
/// the felt one by a few millimetres.
constexpr float kReach_m = 0.01f;

void appendMarker(const haptics::ContactTrace& t, HandJoint joint, const HandPose& drawn,
                  const collision::CollisionScene& world, std::vector<renderer::ContactMarker>& out) {
  if (!t.inContact || out.size() >= renderer::kMaxContactMarkers) return;
  const collision::SphereContact c = world.sphereContact({drawn.at(joint), drawn.radius_m[std::size_t(joint)] + kReach_m});
  if (!c.hit()) return;
  out.push_back({c.point, c.normal, std::clamp(t.intensity, 0.0f, 1.0f)});
}

}  // namespace

void appendContactMarkers(std::span<const haptics::ContactTrace> latest, const haptics::HapticConfig& config,
                          const HandPose& drawn, const collision::CollisionScene& world,
                          std::vector<renderer::ContactMarker>& out) {
  if (!drawn.valid) return;
  const std::size_t count = std::min(latest.size(), config.contacts.size());
  for (std::size_t c = 0; c < count; ++c) appendMarker(latest[c], config.contacts[c].joint, drawn, world, out);
}

void appendContactMarkers(const TouchPipeline& pipeline, const HandPose& drawn, const collision::CollisionScene& world,
                          std::vector<renderer::ContactMarker>& out) {
  if (!drawn.valid) return;
  const auto& contacts = pipeline.contacts();
  const std::size_t count = std::min(contacts.size(), pipeline.config().contacts.size());
  for (std::size_t c = 0; c < count; ++c) appendMarker(contacts[c].last, pipeline.config().contacts[c].joint, drawn, world, out);
}

}  // namespace vt::app
