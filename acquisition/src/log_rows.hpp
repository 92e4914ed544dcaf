#pragma once
// Rows of a scan log (pass, t_s, c0, c1, c2) into passes, with the checks every log format
// shares: integer, contiguous pass indices and strictly increasing timestamps.
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "vt/acquisition/scan.hpp"
#include "vt/core/error.hpp"

namespace vt::acq {

class PassCollector {
 public:
  /// Adds one row; where() names it in errors ("file:12", "file: row 11").
  template <class Where>
  void add(const std::array<double, 5>& f, Where&& where) {
    if (m_passes.empty() || f[0] != m_passValue) {
      startPass(f, where);
    } else if (!(f[1] > m_lastTime_s)) {
      fail(where(), ": non-monotonic timestamps in pass ", m_passes.size() - 1, ": t_s=", f[1], " after t_s=", m_lastTime_s);
    }
    PassSeries& pass = m_passes.back();
    pass.t_s.push_back(f[1]);
    pass.v.push_back({f[2], f[3], f[4]});
    m_lastTime_s = f[1];
  }

  /// The passes; a log without rows is an error naming `source`.
  std::vector<PassSeries> finish(const std::string& source) {
    if (m_passes.empty()) fail(source, ": no samples");
    return std::move(m_passes);
  }

 private:
  // A row whose pass is not the current one's: the next pass begins, or the row is an error.
  template <class Where>
  void startPass(const std::array<double, 5>& f, Where&& where) {
    const double passValue = f[0];
    // In range first, so the conversion is defined; it truncates, so a fraction shows as a
    // difference (cheaper than std::floor, a libm call without SSE4.1).
    if (!(passValue >= 0 && passValue <= 1e6) || double(std::size_t(passValue)) != passValue) {
      fail(where(), ": column 'pass' must be a non-negative integer, got ", passValue);
    }
    const auto pass = std::size_t(passValue);
    if (pass != m_passes.size()) {
      fail(where(), ": pass index ", pass, " out of order (expected ", m_passes.empty() ? 0 : m_passes.size() - 1,
           " or ", m_passes.size(), "; passes must be contiguous from 0)");
    }
    // It must start after the previous one ended.
    if (!m_passes.empty() && f[1] <= m_lastTime_s) {
      fail(where(), ": overlapping timestamps: pass ", pass, " starts at t_s=", f[1], " before pass ", pass - 1,
           " ends at t_s=", m_lastTime_s);
    }
    // Rows per pass are unknown up front: start each pass at the previous pass's size.
    if (!m_passes.empty()) m_expectedRows = m_passes.back().t_s.size() + 16;
    m_passes.emplace_back();
    m_passes.back().t_s.reserve(m_expectedRows);
    m_passes.back().v.reserve(m_expectedRows);
    m_passValue = passValue;
  }

  std::vector<PassSeries> m_passes;
  double m_passValue = 0, m_lastTime_s = 0;  // the current pass's index and its last timestamp
  std::size_t m_expectedRows = 64;
};

}  // namespace vt::acq
