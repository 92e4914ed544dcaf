#include "vt/acquisition/map.hpp"

#include <algorithm>
#include <cmath>

namespace vt::acq {
namespace {

// Bilinear taps of a source position (pixel centres at integer coordinates).
struct Taps {
  int x0, y0;
  float w[4];  // (x0,y0) (x0+1,y0) (x0,y0+1) (x0+1,y0+1)
};

Taps tapsAt(glm::dvec2 p) noexcept {
  // Points a warp sends to (or near) infinity sample nothing instead of overflowing int.
  if (!(std::abs(p.x) < 1e7 && std::abs(p.y) < 1e7)) return {0, 0, {0, 0, 0, 0}};
  const double fx = std::floor(p.x), fy = std::floor(p.y);
  const float ax = float(p.x - fx), ay = float(p.y - fy);
  return {int(fx), int(fy), {(1 - ax) * (1 - ay), ax * (1 - ay), (1 - ax) * ay, ax * ay}};
}

template <class Visit>
void forTaps(const Taps& t, int width, int height, Visit&& visit) {
  const int xs[4] = {t.x0, t.x0 + 1, t.x0, t.x0 + 1}, ys[4] = {t.y0, t.y0, t.y0 + 1, t.y0 + 1};
  for (int k = 0; k < 4; ++k) {
    if (t.w[k] > 0 && xs[k] >= 0 && ys[k] >= 0 && xs[k] < width && ys[k] < height) visit(xs[k], ys[k], t.w[k]);
  }
}

}  // namespace

std::array<double, 9> inverse3x3(const std::array<double, 9>& m) noexcept {
  const double a = m[0], b = m[1], c = m[2], d = m[3], e = m[4], f = m[5], g = m[6], h = m[7], i = m[8];
  const double A = e * i - f * h, B = -(d * i - f * g), C = d * h - e * g;
  const double det = a * A + b * B + c * C;
  const double s = det != 0 ? 1.0 / det : 0.0;
  return {A * s, -(b * i - c * h) * s, (b * f - c * e) * s,
          B * s, (a * i - c * g) * s,  -(a * f - c * d) * s,
          C * s, -(a * h - b * g) * s, (a * e - b * d) * s};
}

std::array<double, 9> multiply3x3(const std::array<double, 9>& a, const std::array<double, 9>& b) noexcept {
  std::array<double, 9> r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) r[std::size_t(i * 3 + j)] += a[std::size_t(i * 3 + k)] * b[std::size_t(k * 3 + j)];
  return r;
}

glm::dvec2 applyHomography(const std::array<double, 9>& h, glm::dvec2 p) noexcept {
  const double w = h[6] * p.x + h[7] * p.y + h[8];
  return {(h[0] * p.x + h[1] * p.y + h[2]) / w, (h[3] * p.x + h[4] * p.y + h[5]) / w};
}

TaxelRaster rasteriseTaxels(std::span<const LineResult> lines, const CameraModel& camera, int width, int height,
                            double stretch_px) {
  ImageF sum(width, height, 1);
  std::vector<int> count(std::size_t(width) * std::size_t(height), 0);
  for (const LineResult& line : lines) {
    for (const Taxel& taxel : line.taxels) {
      const auto w0 = line.world(taxel.y0_m), w1 = line.world(taxel.y1_m);
      const glm::dvec2 p0 = camera.project(w0[0], w0[1]), p1 = camera.project(w1[0], w1[1]);
      const glm::dvec2 along = p1 - p0;
      const double length = glm::length(along);
      const bool finite = std::abs(p0.x) < 1e7 && std::abs(p0.y) < 1e7 && std::abs(p1.x) < 1e7 && std::abs(p1.y) < 1e7;
      if (!finite || !(length > 1e-9)) continue;  // behind or beside the camera: not in the photo
      const glm::dvec2 dir = along / length, normal{-dir.y, dir.x};
      const double pad = stretch_px + 1;
      const int xLo = std::max(0, int(std::floor(std::min(p0.x, p1.x) - pad)));
      const int xHi = std::min(width - 1, int(std::ceil(std::max(p0.x, p1.x) + pad)));
      const int yLo = std::max(0, int(std::floor(std::min(p0.y, p1.y) - pad)));
      const int yHi = std::min(height - 1, int(std::ceil(std::max(p0.y, p1.y) + pad)));
      for (int y = yLo; y <= yHi; ++y) {
        for (int x = xLo; x <= xHi; ++x) {
          const glm::dvec2 d = glm::dvec2(x, y) - p0;
          const double s = glm::dot(d, dir), n = glm::dot(d, normal);
          // Half-open along the line so neighbouring taxels never claim the same pixel twice.
          if (s < 0 || s >= length || std::abs(n) > stretch_px) continue;
          sum.at(x, y) += float(taxel.v_g);
          ++count[std::size_t(y) * std::size_t(width) + std::size_t(x)];
        }
      }
    }
  }
  TaxelRaster raster{ImageF(width, height, 1), Image8(width, height, 1)};
  for (std::size_t i = 0; i < count.size(); ++i) {
    if (count[i] == 0) continue;
    raster.value_g.pixels[i] = sum.pixels[i] / float(count[i]);
    raster.coverage.pixels[i] = 255;
  }
  return raster;
}

Image8 warpImage(const Image8& src, const std::array<double, 9>& H, int width, int height) {
  const auto inv = inverse3x3(H);
  Image8 dst(width, height, src.channels);
  std::vector<float> acc(std::size_t(src.channels));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      std::fill(acc.begin(), acc.end(), 0.0f);
      forTaps(tapsAt(applyHomography(inv, {x, y})), src.width, src.height, [&](int sx, int sy, float w) {
        for (int c = 0; c < src.channels; ++c) acc[std::size_t(c)] += w * float(src.at(sx, sy, c));
      });
      for (int c = 0; c < src.channels; ++c) dst.at(x, y, c) = std::uint8_t(std::clamp(acc[std::size_t(c)] + 0.5f, 0.0f, 255.0f));
    }
  }
  return dst;
}

TaxelRaster warpRaster(const TaxelRaster& src, const std::array<double, 9>& H, int width, int height) {
  const auto inv = inverse3x3(H);
  TaxelRaster dst{ImageF(width, height, 1), Image8(width, height, 1)};
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      float value = 0, weight = 0, total = 0;
      forTaps(tapsAt(applyHomography(inv, {x, y})), src.value_g.width, src.value_g.height, [&](int sx, int sy, float w) {
        total += w;
        if (src.coverage.at(sx, sy) == 0) return;
        value += w * src.value_g.at(sx, sy);
        weight += w;
      });
      // Covered when most of the interpolation weight lands on covered pixels.
      if (weight > 0 && weight >= 0.5f * total) {
        dst.value_g.at(x, y) = value / weight;
        dst.coverage.at(x, y) = 255;
      }
    }
  }
  return dst;
}

ImageF normaliseMap(const TaxelRaster& raster) {
  ImageF out(raster.value_g.width, raster.value_g.height, 1);
  float lo = INFINITY, hi = -INFINITY;
  for (std::size_t i = 0; i < out.pixels.size(); ++i) {
    if (!raster.coverage.pixels[i]) continue;
    lo = std::min(lo, raster.value_g.pixels[i]);
    hi = std::max(hi, raster.value_g.pixels[i]);
  }
  const float range = hi > lo ? hi - lo : 1.0f;
  for (std::size_t i = 0; i < out.pixels.size(); ++i) {
    if (raster.coverage.pixels[i]) out.pixels[i] = (raster.value_g.pixels[i] - lo) / range;
  }
  return out;
}

std::array<std::uint8_t, 3> heatColour(float t) noexcept {
  t = std::clamp(t, 0.0f, 1.0f);
  const float r = std::clamp(3 * t, 0.0f, 1.0f), g = std::clamp(3 * t - 1, 0.0f, 1.0f), b = std::clamp(3 * t - 2, 0.0f, 1.0f);
  return {std::uint8_t(r * 255 + 0.5f), std::uint8_t(g * 255 + 0.5f), std::uint8_t(b * 255 + 0.5f)};
}

}  // namespace vt::acq
