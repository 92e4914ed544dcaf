#include "vt/core/time_alignment.hpp"

#include <algorithm>

namespace vt {

std::int64_t LeadSlew::advance(std::int64_t t_ns, std::int64_t target_ns, bool felt) noexcept {
  if (!m_started || !felt) {
    set(t_ns, target_ns);
    return target_ns;
  }
  const auto step = std::int64_t(kSlew * double(std::max<std::int64_t>(0, t_ns - m_last_ns)));
  const std::int64_t lead = m_lead_ns.load(std::memory_order_relaxed);
  const std::int64_t next = lead + std::clamp(target_ns - lead, -step, step);
  m_lead_ns.store(next, std::memory_order_relaxed);
  m_last_ns = t_ns;
  return next;
}

}  // namespace vt
