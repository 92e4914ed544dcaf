#include <catch2/catch.hpp>

#include <cmath>

#include "test_support.hpp"
#include "ui/canvas.hpp"
#include "ui/touch_figure.hpp"

TEST_CASE("Canvas draws anti-aliased lines and legible text") {
  vt::ui::Canvas canvas(120, 40, {255, 255, 255, 255});
  canvas.line({10, 20}, {110, 20}, {0, 0, 0, 255}, 3.0f);
  CHECK(canvas.image().at(60, 20, 0) == 0);    // on the line
  CHECK(canvas.image().at(60, 30, 0) == 255);  // clear of it
  vt::ui::Canvas text(120, 40, {255, 255, 255, 255});
  text.text({2, 2}, "0.8 Index", {0, 0, 0, 255});
  int ink = 0;
  for (std::size_t i = 0; i < text.image().pixels.size(); i += 4) ink += text.image().pixels[i] < 128;
  CHECK(ink > 40);  // glyphs were drawn
  CHECK(text.textWidth("0.8 Index") > 40.0f);
}

TEST_CASE("Touch figure draws the path where the finger touched and the intensity strips") {
  vt::Image8 texture(64, 32, 4);
  std::fill(texture.pixels.begin(), texture.pixels.end(), std::uint8_t(255));
  vt::ui::FingerSeries index;
  index.name = "index";
  index.color = {200, 0, 0, 255};
  for (int i = 0; i <= 100; ++i) {
    index.t_s.push_back(i * 0.01);
    index.intensity.push_back(0.4f + 0.3f * std::sin(i * 0.3f));
    index.uv.push_back({0.1f + 0.008f * float(i), 0.5f});
    index.inContact.push_back(i >= 10);
  }
  const vt::Image8 figure = vt::ui::makeTouchFigure(texture, {index}, "test");
  vt::savePng(vt::test::outputDir("touch_figure") / "figure.png", figure);
  CHECK(figure.width > 600);
  // The path runs across the middle row of the texture panel (v = 0.5): red pixels there.
  int red = 0;
  for (int x = 0; x < figure.width / 2; ++x) {
    for (int y = 0; y < figure.height; ++y) red += figure.at(x, y, 0) > 150 && figure.at(x, y, 1) < 80;
  }
  CHECK(red > 100);
}
