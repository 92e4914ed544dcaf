#include "ui/touch_figure.hpp"

#include <algorithm>
#include <cstdio>

#include "ui/canvas.hpp"

namespace vt::ui {
namespace {

constexpr glm::u8vec4 kInk{30, 30, 30, 255};
constexpr glm::u8vec4 kGrid{215, 215, 215, 255};
constexpr float kMaxIntensity = 0.8f;  // the paper's axis

std::string format(const char* fmt, double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

}  // namespace

glm::u8vec4 fingerColor(int finger) {
  static constexpr glm::u8vec4 kColors[] = {
      {148, 103, 189, 255}, {214, 39, 40, 255}, {31, 119, 180, 255}, {44, 160, 44, 255}, {255, 127, 14, 255}};
  return kColors[std::clamp(finger, 0, 4)];
}

Image8 makeTouchFigure(const Image8& texture, const std::vector<FingerSeries>& fingers, const std::string& title) {
  constexpr int kPanelH = 420, kMargin = 40, kPlotW = 520;
  const float aspect = texture.empty() ? 1.0f : float(texture.width) / float(texture.height);
  const int texW = int(float(kPanelH) * aspect);
  Canvas canvas(kMargin * 3 + texW + kPlotW + 50, kPanelH + kMargin * 2 + 20, {255, 255, 255, 255});
  canvas.text({float(kMargin), 10.0f}, title, kInk, 1.2f);

  // Left: texture and the contact path of every finger.
  const glm::vec2 texMin(kMargin, kMargin + 10), texMax(kMargin + texW, kMargin + 10 + kPanelH);
  canvas.drawImage(texture, texMin, texMax);
  canvas.strokeRect(texMin, texMax, kInk);
  for (const FingerSeries& f : fingers) {
    for (std::size_t i = 1; i < f.uv.size(); ++i) {
      if (!f.inContact[i] || !f.inContact[i - 1]) continue;
      auto toPixel = [&](glm::vec2 uv) {
        return texMin + glm::vec2(uv.x, 1.0f - uv.y) * (texMax - texMin);  // row = (1 - v) * height
      };
      canvas.line(toPixel(f.uv[i - 1]), toPixel(f.uv[i]), f.color, 2.5f);
    }
  }

  // Right: one intensity strip per finger, shared time axis.
  double tMin = 1e300, tMax = -1e300;
  for (const FingerSeries& f : fingers) {
    if (f.t_s.empty()) continue;
    tMin = std::min(tMin, f.t_s.front());
    tMax = std::max(tMax, f.t_s.back());
  }
  if (!(tMax > tMin)) tMin = 0.0, tMax = 1.0;
  const int rows = std::max<int>(1, int(fingers.size()));
  const float plotX0 = float(kMargin * 2 + texW + 40), plotX1 = plotX0 + float(kPlotW);
  const float rowH = float(kPanelH) / float(rows);
  for (int r = 0; r < rows && r < int(fingers.size()); ++r) {
    const FingerSeries& f = fingers[std::size_t(r)];
    const float y0 = texMin.y + rowH * float(r) + 6.0f, y1 = texMin.y + rowH * float(r + 1) - 18.0f;
    for (float level : {0.0f, 0.4f, 0.8f}) {
      const float y = y1 - (y1 - y0) * level / kMaxIntensity;
      canvas.line({plotX0, y}, {plotX1, y}, kGrid);
      canvas.text({plotX0 - 30.0f, y - 7.0f}, format("%.1f", level), kInk);
    }
    canvas.strokeRect({plotX0, y0}, {plotX1, y1}, kInk);
    canvas.text({plotX1 + 6.0f, y0}, f.name, f.color, 1.0f);
    auto toPlot = [&](double t, float v) {
      return glm::vec2(plotX0 + float((t - tMin) / (tMax - tMin)) * float(kPlotW),
                       y1 - (y1 - y0) * std::clamp(v, 0.0f, kMaxIntensity) / kMaxIntensity);
    };
    for (std::size_t i = 1; i < f.t_s.size(); ++i) {
      canvas.line(toPlot(f.t_s[i - 1], f.intensity[i - 1]), toPlot(f.t_s[i], f.intensity[i]), f.color, 1.5f);
    }
  }
  const float axisY = texMin.y + float(kPanelH) - 2.0f;
  for (int k = 0; k <= 4; ++k) {
    const double t = tMin + (tMax - tMin) * k / 4.0;
    const float x = plotX0 + float(kPlotW) * float(k) / 4.0f;
    canvas.text({x - 12.0f, axisY}, format("%.2f", t), kInk);
  }
  canvas.text({plotX0 + float(kPlotW) * 0.5f - 20.0f, axisY + 16.0f}, "time (s)", kInk);
  canvas.text({plotX0 - 38.0f, texMin.y - 22.0f}, "intensity", kInk);
  return canvas.image();
}

}  // namespace vt::ui
