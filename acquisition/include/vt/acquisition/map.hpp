#pragma once
// Map building: taxels projected into the photo and stretched across their scan line, then
// the optional perspective warp and crop applied identically to photo and map. Any thread.
#include <array>
#include <span>

#include "vt/acquisition/alignment.hpp"
#include "vt/acquisition/calibration.hpp"
#include "vt/scene/image.hpp"

namespace vt::acq {

/// Vibration intensity per photo pixel (mean of the taxels covering it) and where it is known.
struct TaxelRaster {
  ImageF value_g;   // one channel, V in g, 0 where no taxel
  Image8 coverage;  // one channel, 255 where at least one taxel covers the pixel centre
};

/// Draws each taxel as the segment f(line.world(y0))..f(line.world(y1)) widened by stretch_px to both sides.
TaxelRaster rasteriseTaxels(std::span<const LineResult> lines, const CameraModel& camera, int width, int height,
                            double stretch_px);

/// Row-major 3x3 product a * b.
std::array<double, 9> multiply3x3(const std::array<double, 9>& a, const std::array<double, 9>& b) noexcept;
/// Inverse of a row-major 3x3 (zero matrix when singular).
std::array<double, 9> inverse3x3(const std::array<double, 9>& m) noexcept;
/// Applies a row-major 3x3 homography to a pixel.
glm::dvec2 applyHomography(const std::array<double, 9>& h, glm::dvec2 p) noexcept;

/// Bilinear perspective warp (dst = H * src) of any image; pixels mapping outside become 0.
Image8 warpImage(const Image8& src, const std::array<double, 9>& H, int width, int height);
/// Warps a raster: values averaged over covered neighbours only, so edges do not fade to 0.
TaxelRaster warpRaster(const TaxelRaster& src, const std::array<double, 9>& H, int width, int height);

/// Min-max normalises the covered pixels to [0,1] (uncovered stay 0).
ImageF normaliseMap(const TaxelRaster& raster);

/// A colour ramp for previews (black, red, yellow, white) of t in [0,1].
std::array<std::uint8_t, 3> heatColour(float t) noexcept;

}  // namespace vt::acq
