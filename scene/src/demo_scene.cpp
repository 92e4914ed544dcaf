#include "vt/scene/demo_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>

namespace vt {
namespace {

constexpr float kTau = 2.0f * std::numbers::pi_v<float>;

float fract(float x) noexcept { return x - std::floor(x); }

// Integer hash to [0,1): deterministic on every platform, unlike std::rand.
float hash01(int x, int y) noexcept {
  std::uint32_t h = std::uint32_t(x) * 0x8da6b343u ^ std::uint32_t(y) * 0xd8163841u;
  h ^= h >> 13;
  h *= 0x85ebca6bu;
  h ^= h >> 16;
  return float(h & 0xFFFFFFu) / float(0x1000000);
}

float valueNoise(float x, float y) noexcept {
  const int ix = int(std::floor(x)), iy = int(std::floor(y));
  const float fx = x - float(ix), fy = y - float(iy);
  const float sx = fx * fx * (3 - 2 * fx), sy = fy * fy * (3 - 2 * fy);
  const float a = hash01(ix, iy), b = hash01(ix + 1, iy), c = hash01(ix, iy + 1), d = hash01(ix + 1, iy + 1);
  return (a + (b - a) * sx) + ((c + (d - c) * sx) - (a + (b - a) * sx)) * sy;
}

std::uint8_t toByte(float v) noexcept { return std::uint8_t(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f); }

}  // namespace

float patternValue(Pattern pattern, float u, float v) noexcept {
  switch (pattern) {
    case Pattern::Stripes: return 0.5f + 0.5f * std::sin(kTau * 12.0f * u);
    case Pattern::Checker: return float((int(std::floor(u * 8.0f)) + int(std::floor(v * 8.0f))) & 1);
    case Pattern::Dots: {
      const float dx = fract(u * 10.0f) - 0.5f, dy = fract(v * 10.0f) - 0.5f;
      return std::sqrt(dx * dx + dy * dy) < 0.3f ? 1.0f : 0.0f;
    }
    case Pattern::Grid: {
      const float gx = fract(u * 10.0f), gy = fract(v * 10.0f);
      return (gx < 0.15f || gy < 0.15f) ? 1.0f : 0.0f;
    }
    case Pattern::Wood: {
      const float r = std::sqrt((u - 0.2f) * (u - 0.2f) * 0.05f + (v + 0.3f) * (v + 0.3f));
      return 0.5f + 0.5f * std::sin(kTau * (r * 14.0f + 0.6f * valueNoise(u * 6.0f, v * 6.0f)));
    }
    case Pattern::Speckle: return valueNoise(u * 48.0f, v * 48.0f);
  }
  return 0.0f;
}

Image8 makePatternTexture(Pattern pattern, int size, glm::vec3 colorA, glm::vec3 colorB) {
  Image8 image(size, size, 4);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const float u = (float(x) + 0.5f) / float(size);
      const float v = 1.0f - (float(y) + 0.5f) / float(size);  // row 0 is the top (v = 1)
      const float t = patternValue(pattern, u, v);
      const float grain = 0.92f + 0.08f * valueNoise(u * 90.0f, v * 90.0f);
      const glm::vec3 c = glm::mix(colorA, colorB, t) * grain;
      image.at(x, y, 0) = toByte(c.r);
      image.at(x, y, 1) = toByte(c.g);
      image.at(x, y, 2) = toByte(c.b);
      image.at(x, y, 3) = 255;
    }
  }
  return image;
}

ImageF makePatternVibrationMap(Pattern pattern, int size) {
  ImageF map(size, size, 1);
  const float step = 1.0f / float(size);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const float u = (float(x) + 0.5f) * step;
      const float v = 1.0f - (float(y) + 0.5f) * step;
      // Vibration rises where the surface changes height (edges, ridges), as a stylus feels it.
      const float gu = patternValue(pattern, u + step, v) - patternValue(pattern, u - step, v);
      const float gv = patternValue(pattern, u, v + step) - patternValue(pattern, u, v - step);
      map.at(x, y) = std::clamp(0.15f + 0.35f * patternValue(pattern, u, v) + 1.5f * std::sqrt(gu * gu + gv * gv),
                                0.0f, 1.0f);
    }
  }
  return map;
}

Scene makeDemoScene(const DemoSceneOptions& options) {
  Scene scene;
  const int n = options.textureSize;

  // Table top: a wide box whose top face is at y = 0.
  scene.meshes.push_back(makeBox({1.2f, 0.04f, 0.7f}));
  scene.meshes.push_back(makeBox({0.14f, 0.006f, 0.14f}));
  scene.textures.push_back(makePatternTexture(Pattern::Wood, n, {0.45f, 0.28f, 0.15f}, {0.62f, 0.42f, 0.25f}));
  scene.materials.push_back({.name = "table", .albedoTexture = 0});
  scene.objects.push_back({"table", 0, 0, glm::translate(glm::mat4(1.0f), {0.0f, -0.02f, 0.0f})});

  struct PlateSpec {
    const char* name;
    Pattern pattern;
    glm::vec3 a, b;
  };
  const PlateSpec plates[] = {
      {"stripes", Pattern::Stripes, {0.15f, 0.2f, 0.5f}, {0.85f, 0.85f, 0.9f}},
      {"checker", Pattern::Checker, {0.1f, 0.1f, 0.1f}, {0.9f, 0.9f, 0.85f}},
      {"dots", Pattern::Dots, {0.8f, 0.75f, 0.6f}, {0.7f, 0.1f, 0.1f}},
      {"grid", Pattern::Grid, {0.3f, 0.6f, 0.35f}, {0.95f, 0.95f, 0.95f}},
  };
  for (int i = 0; i < 4; ++i) {
    const PlateSpec& spec = plates[i];
    const glm::vec3 b = options.variant == 0 ? spec.b : glm::vec3(1.0f) - spec.b;
    scene.textures.push_back(makePatternTexture(spec.pattern, n, spec.a, b));
    scene.vibrationMaps.push_back(makePatternVibrationMap(spec.pattern, n));
    scene.materials.push_back({.name = spec.name,
                               .albedoTexture = int(scene.textures.size()) - 1,
                               .vibrationMap = int(scene.vibrationMaps.size()) - 1,
                               .physicalWidth_m = 0.14f});
    const float x = -0.27f + 0.18f * float(i);
    scene.objects.push_back({spec.name, 1, int(scene.materials.size()) - 1,
                             glm::translate(glm::mat4(1.0f), {x, 0.003f, 0.0f})});
  }
  scene.camera.target = {0.0f, 0.0f, 0.0f};
  scene.camera.distance_m = 0.75f;
  scene.camera.pitch_rad = -0.85f;
  return scene;
}

Scene makeGratingPlate(float plate_m, float period_m, int pixelsPerPeriod) {
  Scene scene;
  scene.meshes.push_back(makePlane({plate_m, plate_m}, 1));
  const int width = int(std::lround(plate_m / period_m)) * pixelsPerPeriod;
  ImageF map(width, 4, 1);
  // Pixel x covers [x, x+1) / width; its centre sits half a pixel in. Shifting the pattern by
  // half a period's pixels puts each 0 -> 1 transition midway between two pixel centres, at
  // a period boundary.
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < width; ++x) map.at(x, y) = (x % pixelsPerPeriod) < pixelsPerPeriod / 2 ? 1.0f : 0.0f;
  scene.vibrationMaps.push_back(std::move(map));
  Material material;
  material.name = "grating";
  material.vibrationMap = 0;
  material.physicalWidth_m = plate_m;
  scene.materials.push_back(material);
  scene.objects.push_back({"grating", 0, 0, glm::mat4(1.0f)});
  return scene;
}

}  // namespace vt
