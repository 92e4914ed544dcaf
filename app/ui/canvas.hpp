#pragma once
// Figure drawing without a GPU: one interface (FigureSurface) with a raster implementation for
// PNG (Canvas: anti-aliased lines, boxes, images, text set in Dear ImGui's built-in font) and a
// vector one for SVG (ui/svg_surface.hpp). Main thread only.
#include <string_view>

#include <glm/glm.hpp>

#include "vt/scene/image.hpp"

namespace vt::ui {

/// Width in pixels `text` takes in the figures' font; `scale` 1 = 13 px glyphs.
float figureTextWidth(std::string_view text, float scale = 1.0f);

/// Where figures draw; colours are sRGB bytes, coordinates in pixels (y down).
class FigureSurface {
 public:
  virtual ~FigureSurface() = default;
  virtual void fillRect(glm::vec2 min, glm::vec2 max, glm::u8vec4 color) = 0;
  virtual void strokeRect(glm::vec2 min, glm::vec2 max, glm::u8vec4 color, float width = 1.0f) = 0;
  /// A line of the given width (anti-aliased where rasterised).
  virtual void line(glm::vec2 a, glm::vec2 b, glm::u8vec4 color, float width = 1.0f) = 0;
  /// Draws `src` (RGBA8) scaled into the rectangle.
  virtual void drawImage(const Image8& src, glm::vec2 min, glm::vec2 max) = 0;
  /// Text with its top-left corner at `at`, as wide as figureTextWidth says.
  virtual void text(glm::vec2 at, std::string_view text, glm::u8vec4 color, float scale = 1.0f) = 0;
  /// Width in pixels the text would take.
  float textWidth(std::string_view text, float scale = 1.0f) const { return figureTextWidth(text, scale); }
};

/// An RGBA8 raster surface.
class Canvas final : public FigureSurface {
 public:
  Canvas(int width, int height, glm::u8vec4 background);

  void fillRect(glm::vec2 min, glm::vec2 max, glm::u8vec4 color) override;
  void strokeRect(glm::vec2 min, glm::vec2 max, glm::u8vec4 color, float width = 1.0f) override;
  void line(glm::vec2 a, glm::vec2 b, glm::u8vec4 color, float width = 1.0f) override;
  /// Bilinear scaling.
  void drawImage(const Image8& src, glm::vec2 min, glm::vec2 max) override;
  void text(glm::vec2 at, std::string_view text, glm::u8vec4 color, float scale = 1.0f) override;

  const Image8& image() const { return m_image; }

 private:
  void blend(int x, int y, glm::u8vec4 color, float coverage);
  Image8 m_image;
};

}  // namespace vt::ui
