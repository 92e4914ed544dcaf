#pragma once
// The physical scale of a published vibration map, estimated from its taxel pattern: the maps
// are grids of constant cells, 1 mm along a scan line and 2 mm across (lines 2 mm apart), so the
// period of the cell boundaries in pixels gives millimetres per pixel. Any thread.
#include "vt/scene/image.hpp"

namespace vt {

/// Millimetres per pixel from the spacing of the scan lines (`lineSpacing_mm` apart) seen in
/// `map`; 0 when no regular line pattern stands out.
double estimateMmPerPixel(const ImageF& map, double lineSpacing_mm = 2.0);

}  // namespace vt
