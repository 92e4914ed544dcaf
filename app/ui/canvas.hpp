#pragma once
// CPU raster drawing for figures written as PNG (no GPU): lines, boxes, images and text
// set in Dear ImGui's built-in font. Main thread only.
#include <string_view>

#include <glm/glm.hpp>

#include "vt/scene/image.hpp"

namespace vt::ui {

/// An RGBA8 drawing surface; colours are sRGB bytes, coordinates in pixels (y down).
class Canvas {
 public:
  Canvas(int width, int height, glm::u8vec4 background);

  void fillRect(glm::vec2 min, glm::vec2 max, glm::u8vec4 color);
  void strokeRect(glm::vec2 min, glm::vec2 max, glm::u8vec4 color, float width = 1.0f);
  /// Anti-aliased line of the given width.
  void line(glm::vec2 a, glm::vec2 b, glm::u8vec4 color, float width = 1.0f);
  /// Draws `src` (RGBA8) scaled bilinearly into the rectangle.
  void drawImage(const Image8& src, glm::vec2 min, glm::vec2 max);
  /// Text with its top-left corner at `at`; `scale` 1 = 13 px glyphs.
  void text(glm::vec2 at, std::string_view text, glm::u8vec4 color, float scale = 1.0f);
  /// Width in pixels the text would take.
  float textWidth(std::string_view text, float scale = 1.0f) const;

  const Image8& image() const { return m_image; }

 private:
  void blend(int x, int y, glm::u8vec4 color, float coverage);
  Image8 m_image;
};

}  // namespace vt::ui
