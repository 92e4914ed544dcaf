#include "vt/core/time_alignment.hpp"

#include <algorithm>

namespace vt {

std::int64_t LeadSlew::advance(std::int64_t t_ns, std::int64_t target_ns, bool felt) noexcept {
  if (!m_started || !felt) {
    set(t_ns, target_ns);
    return m_lead_ns;
  }
  const auto step = std::int64_t(kSlew * double(std::max<std::int64_t>(0, t_ns - m_last_ns)));
  m_lead_ns += std::clamp(target_ns - m_lead_ns, -step, step);
  m_last_ns = t_ns;
  return m_lead_ns;
}

}  // namespace vt
