#include "ui/touch_figure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ui/canvas.hpp"
#include "ui/svg_surface.hpp"

namespace vt::ui {
namespace {

constexpr glm::u8vec4 kInk{30, 30, 30, 255};
constexpr glm::u8vec4 kGrid{215, 215, 215, 255};
constexpr glm::u8vec4 kWhite{255, 255, 255, 255};
constexpr float kMaxIntensity = 0.8f;  // the paper's axis
constexpr int kPanelH = 420, kMargin = 40, kPlotW = 520;

std::string format(const char* fmt, double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

int photoWidth_px(const Image8& texture) {
  const float aspect = texture.empty() ? 1.0f : float(texture.width) / float(texture.height);
  return int(float(kPanelH) * aspect);
}

glm::ivec2 figureSize(const Image8& texture) { return {kMargin * 3 + photoWidth_px(texture) + kPlotW + 50, kPanelH + kMargin * 2 + 34}; }

// A bar of a round length near a quarter of the photo's width, in its bottom-left corner.
void scaleBar(FigureSurface& out, glm::vec2 photoMin, glm::vec2 photoMax, float photoWidth_m) {
  const double width_mm = double(photoWidth_m) * 1000.0;
  // The longest round length (1, 2 or 5 times a power of ten) up to 30 % of the photo's width.
  const double power = std::pow(10.0, std::floor(std::log10(width_mm * 0.3)));
  double bar_mm = power;
  for (double m : {2.0, 5.0}) {
    if (m * power <= width_mm * 0.3) bar_mm = m * power;
  }
  const float bar_px = float(bar_mm / width_mm) * (photoMax.x - photoMin.x);
  const std::string label = format(bar_mm < 1.0 ? "%.1f mm" : "%.0f mm", bar_mm);
  const glm::vec2 at{photoMin.x + 10.0f, photoMax.y - 14.0f};
  const float boxW = std::max(bar_px, out.textWidth(label)) + 8.0f;
  out.fillRect({at.x - 4.0f, at.y - 18.0f}, {at.x - 4.0f + boxW, at.y + 8.0f}, kWhite);
  out.fillRect(at, {at.x + bar_px, at.y + 4.0f}, kInk);
  out.text({at.x, at.y - 16.0f}, label, kInk);
}

void drawFigure(FigureSurface& out, const Image8& texture, const std::vector<FingerSeries>& fingers,
                const TouchFigureInfo& info) {
  const int texW = photoWidth_px(texture);
  out.text({float(kMargin), 10.0f}, info.title, kInk, 1.2f);

  // Left: the photo and the contact path of every finger.
  const glm::vec2 texMin(kMargin, kMargin + 10), texMax(kMargin + texW, kMargin + 10 + kPanelH);
  out.drawImage(texture, texMin, texMax);
  out.strokeRect(texMin, texMax, kInk);
  for (const FingerSeries& f : fingers) {
    auto toPixel = [&](glm::vec2 uv) {
      return texMin + glm::vec2(uv.x, 1.0f - uv.y) * (texMax - texMin);  // row = (1 - v) * height
    };
    for (std::size_t i = 1; i < f.uv.size(); ++i) {
      if (f.onPath[i] && f.onPath[i - 1]) out.line(toPixel(f.uv[i - 1]), toPixel(f.uv[i]), f.color, 2.5f);
    }
  }
  if (info.photoWidth_m > 0.0f) scaleBar(out, texMin, texMax, info.photoWidth_m);
  if (!info.note.empty()) out.text({texMin.x, texMax.y + 28.0f}, info.note, kInk);

  // Right: one intensity strip per finger, shared time axis with ticks at round times.
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
  const auto timeX = [&](double t) { return plotX0 + float((t - tMin) / (tMax - tMin)) * float(kPlotW); };
  const double step = roundStep(tMax - tMin, 5);
  const int decimals = std::max(0, int(std::ceil(-std::log10(step) - 1e-9)));
  for (int r = 0; r < rows && r < int(fingers.size()); ++r) {
    const FingerSeries& f = fingers[std::size_t(r)];
    const float y0 = texMin.y + rowH * float(r) + 6.0f, y1 = texMin.y + rowH * float(r + 1) - 18.0f;
    for (float level : {0.0f, 0.4f, 0.8f}) {
      const float y = y1 - (y1 - y0) * level / kMaxIntensity;
      out.line({plotX0, y}, {plotX1, y}, kGrid);
      out.text({plotX0 - 30.0f, y - 7.0f}, format("%.1f", level), kInk);
    }
    for (double t = std::ceil(tMin / step) * step; t <= tMax + 1e-9; t += step) out.line({timeX(t), y0}, {timeX(t), y1}, kGrid);
    out.strokeRect({plotX0, y0}, {plotX1, y1}, kInk);
    out.text({plotX1 + 6.0f, y0}, f.name, f.color, 1.0f);
    auto toPlot = [&](double t, float v) {
      return glm::vec2(timeX(t), y1 - (y1 - y0) * std::clamp(v, 0.0f, kMaxIntensity) / kMaxIntensity);
    };
    for (std::size_t i = 1; i < f.t_s.size(); ++i) {
      if (std::isnan(f.intensity[i - 1]) || std::isnan(f.intensity[i])) continue;
      out.line(toPlot(f.t_s[i - 1], f.intensity[i - 1]), toPlot(f.t_s[i], f.intensity[i]), f.color, 1.5f);
    }
  }
  const float axisY = texMin.y + float(kPanelH) - 2.0f;
  for (double t = std::ceil(tMin / step) * step; t <= tMax + 1e-9; t += step) {
    const std::string label = format(("%." + std::to_string(decimals) + "f").c_str(), std::abs(t) < 1e-12 ? 0.0 : t);
    out.text({timeX(t) - out.textWidth(label) * 0.5f, axisY}, label, kInk);
  }
  out.text({plotX0 + float(kPlotW) * 0.5f - 20.0f, axisY + 16.0f}, "time (s)", kInk);
  out.text({plotX0 - 38.0f, texMin.y - 22.0f}, "intensity", kInk);
}

}  // namespace

double roundStep(double range, int parts) {
  if (!(range > 0.0) || parts < 1) return 1.0;
  const double raw = range / double(parts);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0}) {
    if (m * power >= raw * 0.999) return m * power;
  }
  return 10.0 * power;
}

glm::u8vec4 fingerColor(int finger) {
  static constexpr glm::u8vec4 kColors[] = {
      {148, 103, 189, 255}, {214, 39, 40, 255}, {31, 119, 180, 255}, {44, 160, 44, 255}, {255, 127, 14, 255}};
  return kColors[std::clamp(finger, 0, 4)];
}

Image8 makeTouchFigure(const Image8& texture, const std::vector<FingerSeries>& fingers, const TouchFigureInfo& info) {
  const glm::ivec2 size = figureSize(texture);
  Canvas canvas(size.x, size.y, kWhite);
  drawFigure(canvas, texture, fingers, info);
  return canvas.image();
}

std::string makeTouchFigureSvg(const Image8& texture, const std::vector<FingerSeries>& fingers, const TouchFigureInfo& info) {
  const glm::ivec2 size = figureSize(texture);
  SvgSurface svg(size.x, size.y, kWhite);
  drawFigure(svg, texture, fingers, info);
  return svg.document();
}

}  // namespace vt::ui
