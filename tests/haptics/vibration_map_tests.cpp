#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <vector>

#include "test_support.hpp"
#include "vt/core/error.hpp"
#include "vt/haptics/vibration_map.hpp"

using namespace vt;
using namespace vt::haptics;

namespace {

// 2x2 map, rows top-down: row 0 (v near 1) = 0.1 0.2, row 1 (v near 0) = 0.3 0.4.
VibrationMap quadMap() {
  const std::vector<float> values{0.1f, 0.2f, 0.3f, 0.4f};
  return vibrationMapFromFloats(2, 2, values, "quad");
}

void writeBytes(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

template <class T>
void append(std::vector<std::uint8_t>& bytes, T value) {
  std::uint8_t raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  bytes.insert(bytes.end(), raw, raw + sizeof(T));
}

// header.bin + data.bin for `starts` over `samples` (accelerations in g, gravity included).
std::filesystem::path writeWaveforms(const std::string& name, int height, int width, const std::vector<std::int32_t>& starts,
                                     const std::vector<float>& samples) {
  const auto dir = test::outputDir(name);
  std::vector<std::uint8_t> header, data;
  append(header, std::int32_t(height));
  append(header, std::int32_t(width));
  for (auto s : starts) append(header, s);
  for (float s : samples) append(data, s);
  writeBytes(dir / "header.bin", header);
  writeBytes(dir / "data.bin", data);
  return dir;
}

}  // namespace

TEST_CASE("Bilinear sampling uses row = (1 - v) * height and col = u * width") {
  const VibrationMap map = quadMap();
  // Texel centres are exact.
  CHECK(map.sample({0.25f, 0.75f}, false) == Approx(0.1f));
  CHECK(map.sample({0.75f, 0.75f}, false) == Approx(0.2f));
  CHECK(map.sample({0.25f, 0.25f}, false) == Approx(0.3f));
  CHECK(map.sample({0.75f, 0.25f}, false) == Approx(0.4f));
  CHECK(map.sample({0.5f, 0.5f}, false) == Approx(0.25f));
  CHECK(map.sample({0.5f, 0.75f}, false) == Approx(0.15f));
  // Clamp holds the border; wrap blends with the opposite edge.
  CHECK(map.sample({0.0f, 1.0f}, false) == Approx(0.1f));
  CHECK(map.sample({-3.0f, 7.0f}, false) == Approx(0.1f));
  CHECK(map.sample({0.0f, 1.0f}, true) == Approx(0.25f));
  CHECK(map.sample({1.25f, -0.75f}, true) == Approx(0.3f));
  CHECK(map.sample({std::numeric_limits<float>::quiet_NaN(), 0.5f}, true) == 0.0f);
  // Nearest taxel for waveforms follows the same rule.
  CHECK(map.taxel({0.1f, 0.9f}, false) == glm::ivec2(0, 0));
  CHECK(map.taxel({0.9f, 0.1f}, false) == glm::ivec2(1, 1));
  CHECK(map.taxel({1.0f, 0.0f}, false) == glm::ivec2(1, 1));
  CHECK(map.taxel({1.1f, 0.9f}, true) == glm::ivec2(0, 0));
}

TEST_CASE("PNG maps use the red or grey channel at 8 and 16 bits") {
  const auto dir = test::outputDir("png_maps");
  Image8 rgb(2, 1, 3);
  rgb.at(0, 0, 0) = 255;  // red
  rgb.at(1, 0, 1) = 255;  // green only: no vibration
  savePng(dir / "rgb.png", rgb);
  const VibrationMap fromRgb = loadVibrationMapPng(dir / "rgb.png");
  CHECK(fromRgb.intensity().at(0, 0) == Approx(1.0f));
  CHECK(fromRgb.intensity().at(1, 0) == Approx(0.0f));

  Image16 grey(1, 2, 1);
  grey.at(0, 0) = 65535;
  grey.at(0, 1) = 1000;
  savePng16(dir / "grey16.png", grey);
  const VibrationMap fromGrey = loadVibrationMapPng(dir / "grey16.png");
  CHECK(fromGrey.intensity().at(0, 1) == Approx(1000.0f / 65535.0f));
  CHECK(fromGrey.sample({0.5f, 0.75f}, false) == Approx(1.0f));  // top row = v near 1

  CHECK_THROWS_WITH(loadVibrationMapPng(dir / "missing.png"), Catch::Contains("missing.png"));
}

TEST_CASE("Float maps reject wrong sizes and non-finite values and clamp to 0..1") {
  const std::vector<float> ok{-1.0f, 0.5f, 2.0f};
  const VibrationMap map = vibrationMapFromFloats(3, 1, ok, "floats");
  CHECK(map.intensity().pixels == std::vector<float>{0.0f, 0.5f, 1.0f});
  CHECK_THROWS_WITH(vibrationMapFromFloats(2, 2, ok, "floats"), Catch::Contains("floats") && Catch::Contains("3 values"));
  const std::vector<float> nan{0.0f, std::nanf("")};
  CHECK_THROWS_WITH(vibrationMapFromFloats(2, 1, nan, "floats"), Catch::Contains("value 1 is not finite"));
}

TEST_CASE("Taxel waveforms load with gravity removed resampled and normalised") {
  // 1 row x 2 taxels: taxel 0 = four samples alternating 1 +- 0.5 g, taxel 1 = flat 1 g.
  const auto dir = writeWaveforms("waves_ok", 1, 2, {0, 4}, {1.5f, 0.5f, 1.5f, 0.5f, 1.0f, 1.0f});
  const VibrationMap map = loadTaxelWaveforms(dir, {4});
  REQUIRE(map.width() == 2);
  REQUIRE(map.height() == 1);
  CHECK(map.waveforms().peak_g == Approx(0.5f));
  const auto wave0 = map.waveform({0, 0});
  REQUIRE(wave0.size() == 4);
  CHECK(wave0[0] == Approx(1.0f));
  CHECK(wave0[1] == Approx(-1.0f));
  for (float s : map.waveform({1, 0})) CHECK(s == Approx(0.0f).margin(1e-6));
  CHECK(map.intensity().at(0, 0) == Approx(1.0f));  // strongest taxel
  CHECK(map.intensity().at(1, 0) == Approx(0.0f));
  // Resampling to 8 keeps the alternation's extremes within range.
  const VibrationMap longer = loadTaxelWaveforms(dir, {8});
  CHECK(longer.waveform({0, 0}).size() == 8);
  for (float s : longer.waveform({0, 0})) CHECK(std::abs(s) <= 1.0f);
}

TEST_CASE("Malformed taxel waveform files are rejected naming the file") {
  const std::vector<float> samples{1.0f, 1.1f, 0.9f, 1.0f};
  CHECK_THROWS_WITH(loadTaxelWaveforms(test::outputDir("waves_missing")), Catch::Contains("header.bin"));
  CHECK_THROWS_WITH(loadTaxelWaveforms(writeWaveforms("waves_short", 2, 2, {0, 1, 2}, samples)),
                    Catch::Contains("header.bin") && Catch::Contains("expected 24"));
  CHECK_THROWS_WITH(loadTaxelWaveforms(writeWaveforms("waves_size", 0, 2, {}, samples)),
                    Catch::Contains("header.bin") && Catch::Contains("out of range"));
  CHECK_THROWS_WITH(loadTaxelWaveforms(writeWaveforms("waves_decreasing", 1, 3, {0, 3, 2}, samples)),
                    Catch::Contains("header.bin") && Catch::Contains("decreases"));
  CHECK_THROWS_WITH(loadTaxelWaveforms(writeWaveforms("waves_range", 1, 2, {0, 9}, samples)),
                    Catch::Contains("header.bin") && Catch::Contains("outside"));
  CHECK_THROWS_WITH(loadTaxelWaveforms(writeWaveforms("waves_negative", 1, 2, {-1, 2}, samples)),
                    Catch::Contains("header.bin") && Catch::Contains("outside"));
  CHECK_THROWS_WITH(loadTaxelWaveforms(writeWaveforms("waves_nan", 1, 2, {0, 2}, {1.0f, std::nanf(""), 1.0f})),
                    Catch::Contains("data.bin") && Catch::Contains("sample 1 is not finite"));
  const auto odd = writeWaveforms("waves_odd", 1, 1, {0}, samples);
  std::ofstream(odd / "data.bin", std::ios::app) << 'x';
  CHECK_THROWS_WITH(loadTaxelWaveforms(odd), Catch::Contains("data.bin") && Catch::Contains("whole number"));
}
