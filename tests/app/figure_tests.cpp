#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>

#include "test_support.hpp"
#include "ui/canvas.hpp"
#include "ui/svg_surface.hpp"
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
    index.onPath.push_back(i >= 10);
  }
  const vt::Image8 figure = vt::ui::makeTouchFigure(texture, {index}, {.title = "test"});
  vt::savePng(vt::test::outputDir("touch_figure") / "figure.png", figure);
  CHECK(figure.width > 600);
  // The path runs across the middle row of the texture panel (v = 0.5): red pixels there.
  int red = 0;
  for (int x = 0; x < figure.width / 2; ++x) {
    for (int y = 0; y < figure.height; ++y) red += figure.at(x, y, 0) > 150 && figure.at(x, y, 1) < 80;
  }
  CHECK(red > 100);
}

TEST_CASE("Round steps for time ticks and scale bars") {
  CHECK(vt::ui::roundStep(1.72, 5) == Approx(0.5));   // 1.95..3.67 s: ticks every 0.5 s
  CHECK(vt::ui::roundStep(10.0, 5) == Approx(2.0));
  CHECK(vt::ui::roundStep(0.031, 5) == Approx(0.01));
  CHECK(vt::ui::roundStep(95.0, 4) == Approx(50.0));
}

TEST_CASE("Touch figure: millimetre scale bar, gaps while on another object, SVG of the same drawing") {
  vt::Image8 texture(100, 50, 4);
  std::fill(texture.pixels.begin(), texture.pixels.end(), std::uint8_t(230));
  vt::ui::FingerSeries index;
  index.name = "index";
  index.color = {200, 0, 0, 255};
  for (int i = 0; i <= 100; ++i) {
    index.t_s.push_back(1.95 + i * 0.0172);
    index.intensity.push_back(i > 50 && i < 60 ? std::nanf("") : 0.5f);
    index.uv.push_back({0.1f + 0.008f * float(i), 0.5f});
    index.onPath.push_back(true);
  }
  const vt::ui::TouchFigureInfo info{.title = "t & <x>", .photoWidth_m = 0.1f, .note = "side faces: 0.10 s"};
  const vt::Image8 png = vt::ui::makeTouchFigure(texture, {index}, info);
  const std::string svg = vt::ui::makeTouchFigureSvg(texture, {index}, info);
  vt::savePng(vt::test::outputDir("touch_figure") / "scaled.png", png);
  std::ofstream(vt::test::outputDir("touch_figure") / "scaled.svg") << svg;
  // A bar of 20 mm (a round length under a third of the 100 mm photo) and its label.
  CHECK(svg.find(">20 mm</text>") != std::string::npos);
  CHECK(svg.find(">side faces: 0.10 s</text>") != std::string::npos);
  CHECK(svg.find(">t &amp; &lt;x&gt;</text>") != std::string::npos);  // escaped
  CHECK(svg.find("data:image/jpeg;base64,/9j/") != std::string::npos);  // the photo, embedded
  // Time ticks at round values: 2.0, 2.5, 3.0, 3.5 for 1.95..3.67 s.
  for (const char* tick : {">2.0</text>", ">2.5</text>", ">3.0</text>", ">3.5</text>"}) CHECK(svg.find(tick) != std::string::npos);
  CHECK(svg.find(">1.95</text>") == std::string::npos);
  // The raster and the vector figure have the same size.
  CHECK(svg.find("width=\"" + std::to_string(png.width) + "\" height=\"" + std::to_string(png.height) + "\"") != std::string::npos);
  // 100 intensity segments minus the 10 that touch a NaN sample.
  std::size_t red = 0;
  for (std::size_t at = svg.find("stroke=\"rgb(200,0,0)\" stroke-width=\"1.50\""); at != std::string::npos;
       at = svg.find("stroke=\"rgb(200,0,0)\" stroke-width=\"1.50\"", at + 1))
    ++red;
  CHECK(red == 90);
}

TEST_CASE("base64 follows RFC 4648") {
  CHECK(vt::ui::base64("") == "");
  CHECK(vt::ui::base64("f") == "Zg==");
  CHECK(vt::ui::base64("fo") == "Zm8=");
  CHECK(vt::ui::base64("foobar") == "Zm9vYmFy");
}
