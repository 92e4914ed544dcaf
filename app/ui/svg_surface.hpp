#pragma once
// The vector FigureSurface: the same figure written as SVG 1.1 (lines, rectangles, text in a
// monospace font stretched to the raster font's widths, images embedded as base64 JPEG), so a
// paper can scale it without blur. Main thread only.
#include <string>

#include "ui/canvas.hpp"

namespace vt::ui {

/// Collects SVG elements; document() returns the whole file.
class SvgSurface final : public FigureSurface {
 public:
  SvgSurface(int width, int height, glm::u8vec4 background);

  void fillRect(glm::vec2 min, glm::vec2 max, glm::u8vec4 color) override;
  void strokeRect(glm::vec2 min, glm::vec2 max, glm::u8vec4 color, float width = 1.0f) override;
  void line(glm::vec2 a, glm::vec2 b, glm::u8vec4 color, float width = 1.0f) override;
  /// Embeds `src` as a JPEG (quality 92) data URI.
  void drawImage(const Image8& src, glm::vec2 min, glm::vec2 max) override;
  /// XML-escaped; stretched to figureTextWidth so the layout matches the PNG.
  void text(glm::vec2 at, std::string_view text, glm::u8vec4 color, float scale = 1.0f) override;

  /// The complete SVG document.
  std::string document() const { return m_head + m_body + "</svg>\n"; }

 private:
  std::string m_head, m_body;
};

/// Standard base64 (RFC 4648, with padding) of `bytes`.
std::string base64(std::string_view bytes);

}  // namespace vt::ui
