// Texture orientation and material UV handling: a plane with a four-colour texture seen from
// the front, as in the demo scene. Validation layer on.
#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "render_fixture.hpp"
#include "vt/renderer/offscreen_target.hpp"
#include "vt/renderer/renderer.hpp"

using namespace vt;
using namespace vt::test;
using namespace vt::renderer;

namespace {

enum Quadrant { TopLeft, TopRight, BottomLeft, BottomRight };
const glm::u8vec3 kColors[4] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {255, 255, 255}};

// Image quadrants in four colours (row 0 = top of the image).
Image8 quadrantTexture() {
  Image8 t(8, 8, 4);
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 8; ++x) {
      const glm::u8vec3 c = kColors[(y < 4 ? 0 : 2) + (x < 4 ? 0 : 1)];
      for (int k = 0; k < 3; ++k) t.at(x, y, k) = c[k];
      t.at(x, y, 3) = 255;
    }
  }
  return t;
}

/// Which quadrant colour a pixel shows (-1 when none is close).
int classify(const Image8& image, int x, int y) {
  for (int q = 0; q < 4; ++q) {
    bool close = true;
    for (int k = 0; k < 3; ++k) close = close && std::abs(int(image.at(x, y, k)) - int(kColors[q][k])) < 60;
    if (close) return q;
  }
  return -1;
}

/// A unit plane at the origin seen from the front and above; unlit-looking (full ambient).
Image8 renderPlane(const Material& material) {
  Scene scene;
  scene.meshes.push_back(makePlane({1.0f, 1.0f}));
  scene.textures.push_back(quadrantTexture());
  scene.materials.push_back(material);
  scene.materials.back().albedoTexture = 0;
  scene.objects.push_back({"plane", 0, 0, glm::mat4(1.0f)});
  scene.lightDirection = {0.0f, -1.0f, 0.0f};  // straight down: uniform light on the plane
  auto device = validatingDevice();
  Image8 image;
  {
    Renderer r(device);
    r.setScene(std::make_shared<const Scene>(scene));
    OffscreenTarget target(device, 64, 64);
    FrameDesc frame;
    CameraView view;
    view.T_world_eye = glm::inverse(glm::lookAt(glm::vec3(0.0f, 1.6f, 0.5f), glm::vec3(0.0f), glm::vec3(0, 1, 0)));
    setSymmetricFov(view, 0.8f, 1.0f);
    frame.views = {view};
    REQUIRE(r.render(target, frame));
    image = target.readback();
  }
  expectNoValidationMessages(*device);
  return image;
}

}  // namespace

TEST_CASE("textures appear upright seen from the front", "[renderer]") {
  const Image8 image = renderPlane({.name = "quadrants"});
  // The image's top row lies along the far edge (-Z), which is the top of the picture.
  CHECK(classify(image, 24, 24) == TopLeft);
  CHECK(classify(image, 40, 24) == TopRight);
  CHECK(classify(image, 24, 40) == BottomLeft);
  CHECK(classify(image, 40, 40) == BottomRight);
}

TEST_CASE("material uv transform and wrapping are applied", "[renderer]") {
  SECTION("mirror u") {
    Material m{.name = "mirrored"};
    m.uvTransform = glm::mat3(glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(1, 0, 1));  // u' = 1 - u
    const Image8 image = renderPlane(m);
    CHECK(classify(image, 24, 24) == TopRight);
    CHECK(classify(image, 40, 40) == BottomLeft);
  }
  SECTION("repeat twice") {
    Material m{.name = "tiled", .wrapUv = true};
    m.uvTransform = glm::mat3(glm::vec3(2, 0, 0), glm::vec3(0, 2, 0), glm::vec3(0, 0, 1));  // uv' = 2 uv
    const Image8 image = renderPlane(m);
    // The bottom-left quarter of the plane now holds a whole copy of the texture.
    int seen[4] = {0, 0, 0, 0};
    for (int y = 32; y < 48; ++y) {
      for (int x = 16; x < 32; ++x) {
        const int q = classify(image, x, y);
        if (q >= 0) ++seen[q];
      }
    }
    for (int q = 0; q < 4; ++q) CHECK(seen[q] > 0);
  }
}
