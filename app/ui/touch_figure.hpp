#pragma once
// The paper's Fig. 5 as a PNG: the touch path drawn over the texture, beside each finger's
// vibration intensity over time (vertical axis 0 to 0.8). Main thread only.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "vt/scene/image.hpp"

namespace vt::ui {

/// One finger's samples over a run; uv is meaningful only where inContact.
struct FingerSeries {
  std::string name;
  glm::u8vec4 color{255, 0, 0, 255};
  std::vector<double> t_s;
  std::vector<float> intensity;
  std::vector<glm::vec2> uv;
  std::vector<bool> inContact;
};

/// Draws the figure; `texture` is RGBA8 (the touched object's photo), rows top-down.
Image8 makeTouchFigure(const Image8& texture, const std::vector<FingerSeries>& fingers, const std::string& title);

/// Distinct colours for fingers 0..4 (thumb..little).
glm::u8vec4 fingerColor(int finger);

}  // namespace vt::ui
