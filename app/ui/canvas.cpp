#include "ui/canvas.hpp"

#include <algorithm>
#include <cmath>

#include <imgui.h>

namespace vt::ui {
namespace {

// Dear ImGui's embedded font rasterised once on the CPU; glyph lookups are read-only after.
struct FontAtlas {
  ImFontAtlas atlas;
  ImFont* font = nullptr;
  unsigned char* pixels = nullptr;
  int width = 0, height = 0;

  FontAtlas() {
    font = atlas.AddFontDefault();
    atlas.GetTexDataAsAlpha8(&pixels, &width, &height);
  }
  static const FontAtlas& get() {
    static const FontAtlas instance;
    return instance;
  }
};

}  // namespace

Canvas::Canvas(int width, int height, glm::u8vec4 background) : m_image(width, height, 4) {
  for (std::size_t i = 0; i < m_image.pixels.size(); i += 4) {
    for (int c = 0; c < 4; ++c) m_image.pixels[i + std::size_t(c)] = background[c];
  }
}

void Canvas::blend(int x, int y, glm::u8vec4 color, float coverage) {
  if (x < 0 || y < 0 || x >= m_image.width || y >= m_image.height || coverage <= 0.0f) return;
  const float a = std::min(coverage, 1.0f) * float(color.a) / 255.0f;
  for (int c = 0; c < 3; ++c) {
    std::uint8_t& dst = m_image.at(x, y, c);
    dst = std::uint8_t(std::lround(float(dst) * (1.0f - a) + float(color[c]) * a));
  }
  m_image.at(x, y, 3) = 255;
}

void Canvas::fillRect(glm::vec2 min, glm::vec2 max, glm::u8vec4 color) {
  for (int y = int(std::floor(min.y)); y < int(std::ceil(max.y)); ++y) {
    for (int x = int(std::floor(min.x)); x < int(std::ceil(max.x)); ++x) blend(x, y, color, 1.0f);
  }
}

void Canvas::strokeRect(glm::vec2 min, glm::vec2 max, glm::u8vec4 color, float width) {
  line(min, {max.x, min.y}, color, width);
  line({max.x, min.y}, max, color, width);
  line(max, {min.x, max.y}, color, width);
  line({min.x, max.y}, min, color, width);
}

void Canvas::line(glm::vec2 a, glm::vec2 b, glm::u8vec4 color, float width) {
  // Coverage from the distance of each pixel centre to the segment: simple and anti-aliased.
  const float r = width * 0.5f;
  const glm::vec2 lo = glm::floor(glm::min(a, b) - r - 1.0f), hi = glm::ceil(glm::max(a, b) + r + 1.0f);
  const glm::vec2 d = b - a;
  const float len2 = std::max(glm::dot(d, d), 1e-12f);
  for (int y = int(lo.y); y <= int(hi.y); ++y) {
    for (int x = int(lo.x); x <= int(hi.x); ++x) {
      const glm::vec2 p(float(x) + 0.5f, float(y) + 0.5f);
      const float t = std::clamp(glm::dot(p - a, d) / len2, 0.0f, 1.0f);
      const float dist = glm::length(p - (a + d * t));
      blend(x, y, color, r + 0.5f - dist);
    }
  }
}

void Canvas::drawImage(const Image8& src, glm::vec2 min, glm::vec2 max) {
  if (src.empty() || src.channels != 4) return;
  for (int y = int(min.y); y < int(max.y); ++y) {
    for (int x = int(min.x); x < int(max.x); ++x) {
      const float u = (float(x) + 0.5f - min.x) / (max.x - min.x) * float(src.width) - 0.5f;
      const float v = (float(y) + 0.5f - min.y) / (max.y - min.y) * float(src.height) - 0.5f;
      const int x0 = std::clamp(int(std::floor(u)), 0, src.width - 1), x1 = std::min(x0 + 1, src.width - 1);
      const int y0 = std::clamp(int(std::floor(v)), 0, src.height - 1), y1 = std::min(y0 + 1, src.height - 1);
      const float fx = std::clamp(u - float(x0), 0.0f, 1.0f), fy = std::clamp(v - float(y0), 0.0f, 1.0f);
      glm::u8vec4 c;
      for (int k = 0; k < 4; ++k) {
        const float top = float(src.at(x0, y0, k)) * (1 - fx) + float(src.at(x1, y0, k)) * fx;
        const float bottom = float(src.at(x0, y1, k)) * (1 - fx) + float(src.at(x1, y1, k)) * fx;
        c[k] = std::uint8_t(std::lround(top * (1 - fy) + bottom * fy));
      }
      blend(x, y, c, 1.0f);
    }
  }
}

float figureTextWidth(std::string_view text, float scale) {
  const FontAtlas& f = FontAtlas::get();
  float w = 0.0f;
  for (char ch : text) {
    if (const ImFontGlyph* g = f.font->FindGlyph(ImWchar(static_cast<unsigned char>(ch)))) w += g->AdvanceX * scale;
  }
  return w;
}

void Canvas::text(glm::vec2 at, std::string_view text, glm::u8vec4 color, float scale) {
  const FontAtlas& f = FontAtlas::get();
  float penX = at.x;
  for (char ch : text) {
    const ImFontGlyph* g = f.font->FindGlyph(ImWchar(static_cast<unsigned char>(ch)));
    if (!g) continue;
    const int gw = int(std::lround((g->X1 - g->X0) * scale)), gh = int(std::lround((g->Y1 - g->Y0) * scale));
    for (int y = 0; y < gh; ++y) {
      for (int x = 0; x < gw; ++x) {
        const float u = g->U0 + (g->U1 - g->U0) * (float(x) + 0.5f) / float(gw);
        const float v = g->V0 + (g->V1 - g->V0) * (float(y) + 0.5f) / float(gh);
        const int ax = std::clamp(int(u * float(f.width)), 0, f.width - 1);
        const int ay = std::clamp(int(v * float(f.height)), 0, f.height - 1);
        const float coverage = float(f.pixels[ay * f.width + ax]) / 255.0f;
        blend(int(penX + g->X0 * scale) + x, int(at.y + g->Y0 * scale) + y, color, coverage);
      }
    }
    penX += g->AdvanceX * scale;
  }
}

}  // namespace vt::ui
