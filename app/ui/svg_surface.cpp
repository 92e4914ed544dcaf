#include "ui/svg_surface.hpp"

#include <cstdio>

#include "vt/scene/jpeg.hpp"

namespace vt::ui {
namespace {

// The figures draw opaque colours; alpha is ignored.
std::string rgb(glm::u8vec4 c) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "rgb(%d,%d,%d)", c.r, c.g, c.b);
  return buf;
}

std::string num(float v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", double(v));
  return buf;
}

}  // namespace

std::string base64(std::string_view bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t v = std::uint32_t(std::uint8_t(bytes[i])) << 16;
    if (n > 1) v |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
    if (n > 2) v |= std::uint32_t(std::uint8_t(bytes[i + 2]));
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += n > 1 ? kAlphabet[(v >> 6) & 63] : '=';
    out += n > 2 ? kAlphabet[v & 63] : '=';
  }
  return out;
}

SvgSurface::SvgSurface(int width, int height, glm::u8vec4 background) {
  m_head = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" "
           "xmlns:xlink=\"http://www.w3.org/1999/xlink\" version=\"1.1\" width=\"" +
           std::to_string(width) + "\" height=\"" + std::to_string(height) + "\" viewBox=\"0 0 " + std::to_string(width) +
           " " + std::to_string(height) + "\">\n";
  fillRect({0.0f, 0.0f}, {float(width), float(height)}, background);
}

void SvgSurface::fillRect(glm::vec2 min, glm::vec2 max, glm::u8vec4 color) {
  m_body += "<rect x=\"" + num(min.x) + "\" y=\"" + num(min.y) + "\" width=\"" + num(max.x - min.x) + "\" height=\"" +
            num(max.y - min.y) + "\" fill=\"" + rgb(color) + "\"/>\n";
}

void SvgSurface::strokeRect(glm::vec2 min, glm::vec2 max, glm::u8vec4 color, float width) {
  m_body += "<rect x=\"" + num(min.x) + "\" y=\"" + num(min.y) + "\" width=\"" + num(max.x - min.x) + "\" height=\"" +
            num(max.y - min.y) + "\" fill=\"none\" stroke=\"" + rgb(color) + "\" stroke-width=\"" + num(width) + "\"/>\n";
}

void SvgSurface::line(glm::vec2 a, glm::vec2 b, glm::u8vec4 color, float width) {
  m_body += "<line x1=\"" + num(a.x) + "\" y1=\"" + num(a.y) + "\" x2=\"" + num(b.x) + "\" y2=\"" + num(b.y) +
            "\" stroke=\"" + rgb(color) + "\" stroke-width=\"" + num(width) + "\" stroke-linecap=\"round\"/>\n";
}

void SvgSurface::drawImage(const Image8& src, glm::vec2 min, glm::vec2 max) {
  const std::vector<std::uint8_t> jpeg = encodeJpeg(src, 92);
  m_body += "<image x=\"" + num(min.x) + "\" y=\"" + num(min.y) + "\" width=\"" + num(max.x - min.x) + "\" height=\"" +
            num(max.y - min.y) + "\" preserveAspectRatio=\"none\" xlink:href=\"data:image/jpeg;base64," +
            base64({reinterpret_cast<const char*>(jpeg.data()), jpeg.size()}) + "\"/>\n";
}

void SvgSurface::text(glm::vec2 at, std::string_view text, glm::u8vec4 color, float scale) {
  std::string escaped;
  for (char ch : text) {
    switch (ch) {
      case '&': escaped += "&amp;"; break;
      case '<': escaped += "&lt;"; break;
      case '>': escaped += "&gt;"; break;
      case '"': escaped += "&quot;"; break;
      default: escaped += ch;
    }
  }
  // The raster font's cap line is about 3 px below the glyph box's top and its baseline 10 px.
  m_body += "<text x=\"" + num(at.x) + "\" y=\"" + num(at.y + 10.0f * scale) + "\" font-family=\"monospace\" font-size=\"" +
            num(12.0f * scale) + "\" textLength=\"" + num(figureTextWidth(text, scale)) +
            "\" lengthAdjust=\"spacingAndGlyphs\" fill=\"" + rgb(color) + "\">" + escaped + "</text>\n";
}

}  // namespace vt::ui
