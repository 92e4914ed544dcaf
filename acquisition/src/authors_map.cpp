#include "vt/acquisition/authors_map.hpp"

#include <algorithm>
#include <cmath>

#include "vt/acquisition/map.hpp"

namespace vt::acq {
namespace {

// A Python slice [start:stop] of a sequence of `length` items, as the half-open range it selects
// (negative bounds count from the end; an empty range when stop <= start).
std::array<int, 2> pythonSlice(int start, int stop, int length) noexcept {
  const auto clamp = [length](int i) { return std::clamp(i < 0 ? i + length : i, 0, length); };
  const int lo = clamp(start), hi = clamp(stop);
  return {lo, std::max(lo, hi)};
}

// np.round(float32 value).astype(int32): half to even.
int roundAsNumpy(double value) noexcept { return int(std::nearbyint(float(value))); }

}  // namespace

ImageF drawTaxelsAsAuthors(std::span<const LineResult> lines, const CameraModel& camera, int width, int height) {
  ImageF map(width, height, 1);
  for (const LineResult& line : lines) {
    if (line.taxels.empty()) continue;
    // World points go through float32 (their np.float32 array) before cv2.projectPoints; the
    // projected points come back as float32; a line's rows are replaced by their mean.
    const double x = float(line.firstPassX_m);
    std::vector<std::array<double, 2>> ends;
    double rowSum = 0;
    for (const Taxel& t : line.taxels) {
      for (const double along : {t.y0_m, t.y1_m}) {
        const auto w = line.axis == 1 ? std::array<double, 2>{x, double(float(along))} : std::array<double, 2>{double(float(along)), x};
        const glm::dvec2 p = camera.project(w[0], w[1]);
        ends.push_back({double(float(p.x)), double(float(p.y))});
        rowSum += float(p.y);
      }
    }
    const int y = roundAsNumpy(float(rowSum / double(ends.size())));
    const auto rows = pythonSlice(y - 4, y + 4, height);
    for (std::size_t i = 0; i < line.taxels.size(); ++i) {
      // acc_matrix[y - 4 : y2 + 4, x2 : x] = value: columns from the end point to the start point.
      const int x1 = roundAsNumpy(ends[2 * i][0]), x2 = roundAsNumpy(ends[2 * i + 1][0]);
      const auto cols = pythonSlice(x2, x1, width);
      const float value = float(line.taxels[i].v_g);
      for (int r = rows[0]; r < rows[1]; ++r)
        for (int c = cols[0]; c < cols[1]; ++c) map.at(c, r) = value;
    }
  }
  return map;
}

ImageF warpAsOpenCv(const ImageF& src, const std::array<double, 9>& H, int width, int height) {
  constexpr int kSteps = 32;  // OpenCV's INTER_TAB_SIZE: source positions in 1/32 pixel
  const auto M = inverse3x3(H);
  ImageF dst(width, height, 1);
  const auto tap = [&](int sx, int sy) {
    return sx >= 0 && sy >= 0 && sx < src.width && sy < src.height ? src.at(sx, sy) : 0.0f;
  };
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      double w = M[6] * x + M[7] * y + M[8];
      w = w != 0.0 ? kSteps / w : 0.0;
      const double fx = std::clamp((M[0] * x + M[1] * y + M[2]) * w, double(INT32_MIN), double(INT32_MAX));
      const double fy = std::clamp((M[3] * x + M[4] * y + M[5]) * w, double(INT32_MIN), double(INT32_MAX));
      const auto X = int(std::nearbyint(fx)), Y = int(std::nearbyint(fy));
      const int sx = X >> 5, sy = Y >> 5;
      const float ax = float(X & (kSteps - 1)) / kSteps, ay = float(Y & (kSteps - 1)) / kSteps;
      const float w00 = (1.0f - ay) * (1.0f - ax), w01 = (1.0f - ay) * ax, w10 = ay * (1.0f - ax), w11 = ay * ax;
      dst.at(x, y) = tap(sx, sy) * w00 + tap(sx + 1, sy) * w01 + tap(sx, sy + 1) * w10 + tap(sx + 1, sy + 1) * w11;
    }
  }
  return dst;
}

Image8 authorsMap(std::span<const LineResult> lines, const CameraModel& camera, int photoWidth, int photoHeight,
                  const std::optional<std::array<double, 9>>& H, std::array<int, 2> warpSize,
                  const std::optional<std::array<int, 4>>& crop) {
  ImageF map = drawTaxelsAsAuthors(lines, camera, photoWidth, photoHeight);
  // acc_matrix * (1 / acc_matrix.max()), in float32.
  const float peak = *std::max_element(map.pixels.begin(), map.pixels.end());
  // Nothing drawn (a camera seeing the lines run left to right leaves run.py's x2:x slices
  // empty): their 0 / 0 gives NaN, which cv2.imwrite stores as 0.
  const float scale = peak > 0.0f ? 1.0f / peak : 0.0f;
  for (float& v : map.pixels) v *= scale;
  if (H) map = warpAsOpenCv(map, *H, warpSize[0] > 0 ? warpSize[0] : photoWidth, warpSize[1] > 0 ? warpSize[1] : photoHeight);
  const std::array<int, 4> c = crop ? *crop : std::array<int, 4>{0, 0, map.width, map.height};
  Image8 out(c[2], c[3], 1);
  for (int y = 0; y < c[3]; ++y) {
    for (int x = 0; x < c[2]; ++x) {
      // cv2.imwrite of a float image: saturate_cast<uchar>, rounding half to even.
      const float v = map.at(c[0] + x, c[1] + y) * 255.0f;
      out.at(x, y) = std::uint8_t(std::clamp(std::nearbyint(v), 0.0f, 255.0f));
    }
  }
  return out;
}

}  // namespace vt::acq
