#pragma once
// The map as the authors' run.py (wmtlab/Pixel2Taxel) draws it, for `--compat reference`: each
// taxel a rectangle of rows y - 4 .. y + 3 (y: the line's mean projected row) between its rounded
// end columns, later lines overwriting earlier ones, divided by its maximum, warped bilinearly
// with OpenCV's 1/32-pixel coordinate steps (uncovered zeros blended in), cropped and saved as
// 8 bits (docs/scan-format.md, "--compat reference"). Any thread.
#include <array>
#include <optional>
#include <span>

#include "vt/acquisition/alignment.hpp"
#include "vt/acquisition/calibration.hpp"
#include "vt/scene/image.hpp"

namespace vt::acq {

/// The unnormalised drawing (run.py's acc_matrix) in the photo's pixel grid, float32 like theirs.
ImageF drawTaxelsAsAuthors(std::span<const LineResult> lines, const CameraModel& camera, int width, int height);

/// cv2.warpPerspective(src, H, (width, height)) with INTER_LINEAR and a constant 0 border: the
/// source position of each output pixel rounded to 1/32 pixel, then bilinear over the four taps.
ImageF warpAsOpenCv(const ImageF& src, const std::array<double, 9>& H, int width, int height);

/// The whole of run.py's map: drawn, divided by its maximum, warped (when `H`), cropped (when
/// `crop`, x y w h) and rounded to 8 bits as cv2.imwrite stores a float image.
Image8 authorsMap(std::span<const LineResult> lines, const CameraModel& camera, int photoWidth, int photoHeight,
                  const std::optional<std::array<double, 9>>& H, std::array<int, 2> warpSize,
                  const std::optional<std::array<int, 4>>& crop);

}  // namespace vt::acq
