#pragma once
// The paper's Fig. 5: the touch path drawn over the object's photo (with a millimetre scale bar
// when the photo's physical width is known), beside each finger's vibration intensity over time
// (vertical axis 0 to 0.8, time ticks at round values). Raster (PNG) and vector (SVG) from the
// same drawing. Main thread only.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "vt/scene/image.hpp"

namespace vt::ui {

/// One finger's samples over a run. `uv` is drawn where `onPath`; an intensity that is NaN is
/// left out of the strip (the finger was on another object then).
struct FingerSeries {
  std::string name;
  glm::u8vec4 color{255, 0, 0, 255};
  std::vector<double> t_s;
  std::vector<float> intensity;
  std::vector<glm::vec2> uv;
  std::vector<bool> onPath;
};

/// What the figure says besides the series.
struct TouchFigureInfo {
  std::string title;
  float photoWidth_m = 0.0f;  // physical width of the photo (0 = unknown: no scale bar)
  std::string note;           // a line under the photo (e.g. contacts not drawn), may be empty
};

/// The figure as RGBA8; `texture` is RGBA8 (the touched object's photo), rows top-down.
Image8 makeTouchFigure(const Image8& texture, const std::vector<FingerSeries>& fingers, const TouchFigureInfo& info);
/// The same figure as an SVG document (the photo embedded as JPEG).
std::string makeTouchFigureSvg(const Image8& texture, const std::vector<FingerSeries>& fingers, const TouchFigureInfo& info);

/// Distinct colours for fingers 0..4 (thumb..little).
glm::u8vec4 fingerColor(int finger);

/// A round step (1, 2 or 5 times a power of ten) that cuts `range` into about `parts` pieces.
double roundStep(double range, int parts);

}  // namespace vt::ui
