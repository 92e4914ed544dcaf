#include <catch2/catch.hpp>

#include <fstream>

#include <nlohmann/json.hpp>

#include "test_support.hpp"
#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/scene/loaders.hpp"

using Catch::Matchers::Contains;

namespace {

// A 0.1 m quad in the XZ plane: 4 positions, 4 UVs, 6 uint16 indices, in one buffer.
std::vector<std::uint8_t> quadBuffer() {
  const float positions[] = {-0.05f, 0, 0.05f, 0.05f, 0, 0.05f, 0.05f, 0, -0.05f, -0.05f, 0, -0.05f};
  const float uvs[] = {0, 1, 1, 1, 1, 0, 0, 0};  // glTF: v = 0 at the image's top row (far edge)
  const std::uint16_t indices[] = {0, 1, 2, 0, 2, 3};
  std::vector<std::uint8_t> bytes(sizeof positions + sizeof uvs + sizeof indices);
  std::memcpy(bytes.data(), positions, sizeof positions);
  std::memcpy(bytes.data() + sizeof positions, uvs, sizeof uvs);
  std::memcpy(bytes.data() + sizeof positions + sizeof uvs, indices, sizeof indices);
  return bytes;
}

nlohmann::json quadGltf() {
  return {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}, {"name", "plate"}, {"translation", {0.0, 0.01, 0.0}}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 2}, {"material", 0}}}}}}},
      {"materials", {{{"name", "stripes"},
                      {"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 0.5, 0.5, 1.0}}}},
                      {"extras", {{"vtouching", {{"vibration_map", "map.png"}, {"gain", 0.8}, {"wrap", true}}}}}}}},
      {"buffers", {{{"uri", "quad.bin"}, {"byteLength", 92}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
                       {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 32}},
                       {{"buffer", 0}, {"byteOffset", 80}, {"byteLength", 12}}}},
      {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"},
                      {"min", {-0.05, 0, -0.05}}, {"max", {0.05, 0, 0.05}}},
                     {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
                     {{"bufferView", 2}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}},
  };
}

std::filesystem::path writeQuad(const std::filesystem::path& dir, const nlohmann::json& gltf) {
  const auto bytes = quadBuffer();
  std::ofstream(dir / "quad.bin", std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), long(bytes.size()));
  vt::Image8 map(4, 2, 1);
  for (int x = 0; x < 4; ++x) map.at(x, 0) = std::uint8_t(60 * x);
  vt::savePng(dir / "map.png", map);
  std::ofstream(dir / "quad.gltf") << gltf.dump(1);
  return dir / "quad.gltf";
}

}  // namespace

TEST_CASE("glTF quad loads with its transform, flipped UVs and tactile extras") {
  const auto dir = vt::test::outputDir("gltf_quad");
  const vt::Scene scene = vt::loadGltfScene(writeQuad(dir, quadGltf()));
  REQUIRE(scene.objects.size() == 1);
  CHECK(scene.objects[0].name == "plate");
  CHECK(scene.objects[0].T_world_object[3].y == Approx(0.01f));
  const vt::Mesh& mesh = scene.meshes[0];
  REQUIRE(mesh.triangleCount() == 2);
  CHECK(mesh.vertices[0].uv == glm::vec2(0, 0));  // near edge: bottom of the image in our convention
  CHECK(mesh.vertices[2].uv == glm::vec2(1, 1));
  CHECK(mesh.vertices[0].normal.y == Approx(1.0f));  // computed: the file has no normals
  const vt::Material& m = scene.materials[0];
  CHECK(m.name == "stripes");
  CHECK(m.tactileGain == Approx(0.8f));
  CHECK(m.wrapUv);
  CHECK(m.baseColor.g == Approx(0.5f));
  REQUIRE(m.vibrationMap == 0);
  CHECK(scene.vibrationMaps[0].at(3, 0) == Approx(180.0f / 255.0f).margin(1e-3));
}

TEST_CASE("glTF errors name the file and the problem") {
  const auto dir = vt::test::outputDir("gltf_errors");
  REQUIRE_THROWS_WITH(vt::loadGltfScene(dir / "missing.gltf"), Contains("missing.gltf") && Contains("not found"));

  std::ofstream(dir / "broken.gltf") << "{ \"asset\": ";
  REQUIRE_THROWS_WITH(vt::loadGltfScene(dir / "broken.gltf"), Contains("broken.gltf") && Contains("not a valid glTF"));

  auto outOfBounds = quadGltf();
  outOfBounds["accessors"][0]["count"] = 40;
  REQUIRE_THROWS_WITH(vt::loadGltfScene(writeQuad(dir, outOfBounds)), Contains("quad.gltf"));

  auto badIndex = quadGltf();
  auto bytes = quadBuffer();
  bytes[80] = 9;  // first index -> 9, past the 4 vertices
  const auto path = writeQuad(dir, badIndex);
  std::ofstream(dir / "quad.bin", std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), long(bytes.size()));
  REQUIRE_THROWS_WITH(vt::loadGltfScene(path), Contains("index 9 out of range"));

  auto badGain = quadGltf();
  badGain["materials"][0]["extras"]["vtouching"]["gain"] = "loud";
  REQUIRE_THROWS_WITH(vt::loadGltfScene(writeQuad(dir, badGain)), Contains("gain must be a number"));

  auto missingMap = quadGltf();
  missingMap["materials"][0]["extras"]["vtouching"]["vibration_map"] = "nope.png";
  REQUIRE_THROWS_WITH(vt::loadGltfScene(writeQuad(dir, missingMap)), Contains("nope.png") && Contains("not found"));
}

TEST_CASE("glTF sizes from the file cannot wrap, multiply work or hold NaN") {
  const auto dir = vt::test::outputDir("gltf_hostile");
  // count * stride and count * 3 would wrap to small numbers in 64 bits.
  for (const std::uint64_t count : {6148914691236517206ull, 1ull << 63, ~0ull}) {
    auto wraps = quadGltf();
    wraps["accessors"][0]["count"] = count;
    REQUIRE_THROWS_WITH(vt::loadGltfScene(writeQuad(dir, wraps)), Contains("POSITION accessor") && Contains("past the end"));
    auto indices = quadGltf();
    indices["accessors"][2]["count"] = count;
    REQUIRE_THROWS_WITH(vt::loadGltfScene(writeQuad(dir, indices)), Contains("indices accessor") && Contains("past the end"));
  }
  // 61 nodes, each listing its child twice: 2^60 visits within the depth limit.
  auto fanout = quadGltf();
  fanout["nodes"] = nlohmann::json::array();
  for (int i = 0; i < 60; ++i) fanout["nodes"].push_back({{"children", {i + 1, i + 1}}});
  fanout["nodes"].push_back({{"mesh", 0}});
  REQUIRE_THROWS_WITH(vt::loadGltfScene(writeQuad(dir, fanout)), Contains("node visits"));
  auto infinite = quadGltf();
  infinite["nodes"][0]["translation"] = {0.0, 1e300, 0.0};  // a float overflows to infinity
  REQUIRE_THROWS_WITH(vt::loadGltfScene(writeQuad(dir, infinite)), Contains("NaN or infinite transform"));
}

TEST_CASE("glTF mesh instances are held to the vertex budget before they are copied") {
  const auto dir = vt::test::outputDir("gltf_instances");
  // One 512-vertex mesh (6 KiB) under a chain of nodes each listing its child twice: 2^levels instances.
  const std::vector<char> positions(512 * 12, 0);
  std::ofstream(dir / "many.bin", std::ios::binary).write(positions.data(), long(positions.size()));
  const auto scene = [&](int levels) {
    auto gltf = quadGltf();
    gltf["materials"][0]["extras"]["vtouching"].erase("vibration_map");
    gltf["buffers"] = {{{"uri", "many.bin"}, {"byteLength", positions.size()}}};
    gltf["bufferViews"] = {{{"buffer", 0}, {"byteLength", positions.size()}}};
    gltf["accessors"] = {{{"bufferView", 0}, {"componentType", 5126}, {"count", 512}, {"type", "VEC3"}}};
    gltf["meshes"][0]["primitives"][0]["attributes"] = {{"POSITION", 0}};
    gltf["meshes"][0]["primitives"][0].erase("indices");
    gltf["nodes"] = nlohmann::json::array();
    for (int i = 0; i < levels; ++i) gltf["nodes"].push_back({{"children", {i + 1, i + 1}}});
    gltf["nodes"].push_back({{"mesh", 0}});
    std::ofstream(dir / "many.gltf") << gltf.dump();
    return dir / "many.gltf";
  };
  const vt::Scene few = vt::loadGltfScene(scene(4));
  CHECK(few.objects.size() == 16);
  CHECK(few.meshes.at(15).vertices.size() == 512);
  // 2^15 instances (65535 node visits, under that budget) x 512 vertices = 2^24 vertices.
  static_assert((512ull << 15) > vt::budget::kSceneVertices && 65535 < vt::budget::kSceneNodeVisits);
  REQUIRE_THROWS_WITH(vt::loadGltfScene(scene(15)),
                      Contains("many.gltf") && Contains("32768 mesh instances hold more than 8388608 vertices"));
}

TEST_CASE("glTF URIs stay inside the scene folder unless allowed") {
  const auto root = vt::test::outputDir("gltf_confined");
  std::filesystem::create_directories(root / "scene");
  auto outside = quadGltf();
  outside["materials"][0]["extras"]["vtouching"]["vibration_map"] = "../map.png";
  const auto path = writeQuad(root / "scene", outside);
  vt::savePng(root / "map.png", vt::Image8(4, 2, 1));
  REQUIRE_THROWS_WITH(vt::loadGltfScene(path), Contains("vibration_map") && Contains("outside the scene folder"));
  CHECK(vt::loadGltfScene(path, {.allowOutsideFolder = true}).vibrationMaps.size() == 1);

  auto buffer = quadGltf();
  buffer["buffers"][0]["uri"] = "../quad.bin";
  writeQuad(root, quadGltf());  // the buffer exists one level up
  REQUIRE_THROWS_WITH(vt::loadGltfScene(writeQuad(root / "scene", buffer)),
                      Contains("quad.bin' is outside the scene folder") && !Contains("\n"));

  // Refused in the same words whether or not the target exists (the checkout's depth decides
  // where a chain of '..' lands).
  auto missing = quadGltf();
  missing["buffers"][0]["uri"] = "../no-such-folder/quad.bin";
  REQUIRE_THROWS_WITH(vt::loadGltfScene(writeQuad(root / "scene", missing)),
                      Contains("no-such-folder/quad.bin' is outside the scene folder"));
}

TEST_CASE("Dataset directory becomes plates with photo textures and aligned vibration maps") {
  const auto dir = vt::test::outputDir("dataset_small");
  for (const char* name : {"alpha", "beta"}) {
    std::filesystem::create_directories(dir / name);
    vt::savePng(dir / name / (std::string(name) + ".png"), vt::Image8(40, 20, 3));
    vt::Image8 acc(40, 20, 3);
    acc.at(10, 5, 0) = 255;
    vt::savePng(dir / name / (std::string(name) + "_acc.png"), acc);
  }
  std::ofstream(dir / "beta" / "beta_map.json") << R"({"mm_per_pixel": 1.0})";
  const vt::Scene scene = vt::loadDatasetScene(dir);
  REQUIRE(scene.objects.size() == 3);  // two plates and the table
  CHECK(scene.objects[0].name == "alpha");
  CHECK(scene.materials[0].physicalWidth_m == Approx(40 * vt::kDefaultMmPerPixel * 1e-3));
  CHECK(scene.materials[1].physicalWidth_m == Approx(0.040f));
  CHECK(scene.vibrationMaps[0].at(10, 5) == Approx(1.0f));
  const vt::Scene overridden = vt::loadDatasetScene(dir, {.mmPerPixel = 0.5});
  CHECK(overridden.materials[1].physicalWidth_m == Approx(0.020f));
}

TEST_CASE("Dataset errors name the object and the problem") {
  const auto dir = vt::test::outputDir("dataset_bad");
  REQUIRE_THROWS_WITH(vt::loadDatasetScene(dir), Contains("no NAME/NAME.png"));
  std::filesystem::create_directories(dir / "gamma");
  vt::savePng(dir / "gamma" / "gamma.png", vt::Image8(40, 20, 3));
  vt::savePng(dir / "gamma" / "gamma_acc.png", vt::Image8(41, 20, 3));
  REQUIRE_THROWS_WITH(vt::loadDatasetScene(dir), Contains("gamma") && Contains("pixel-aligned"));
}

TEST_CASE("The published Pixel2Taxel dataset loads as eight plates") {
  const auto dataset = vt::test::datasetDir();
  if (!dataset) VT_SKIP("dataset not present at " VT_DATASET_DIR);
  const vt::Scene scene = vt::loadDatasetScene(*dataset);
  CHECK(scene.objects.size() == 9);
  for (std::size_t i = 0; i + 1 < scene.objects.size(); ++i) {
    const vt::Material& m = scene.materials[std::size_t(scene.objects[i].material)];
    const vt::ImageF& map = scene.vibrationMaps[std::size_t(m.vibrationMap)];
    const vt::Image8& photo = scene.textures[std::size_t(m.albedoTexture)];
    CHECK(map.width == photo.width);
    CHECK(map.height == photo.height);
    CHECK(m.physicalWidth_m > 0.05f);
    CHECK(m.physicalWidth_m < 0.3f);
  }
}

TEST_CASE("glTF JSON is checked before it is parsed: nesting, 32-bit indices, the bytes it references") {
  const auto dir = vt::test::outputDir("gltf_json_checks");
  // 20,000 nested arrays in a material's extras overflowed the stack of tinygltf's extras reader.
  writeQuad(dir, quadGltf());
  std::string text = quadGltf().dump();
  text.replace(text.find("\"extras\":{"), 10, "\"extras\":{\"deep\":" + std::string(20000, '[') + std::string(20000, ']') + ",");
  std::ofstream(dir / "deep.gltf") << text;
  REQUIRE_THROWS_WITH(vt::loadGltfScene(dir / "deep.gltf"), Contains("deep.gltf") && Contains("JSON nested deeper than 64 levels"));
  // Indices are 32-bit: 2^32 + 0 used to load as material 0, texture 0, ...
  auto material = quadGltf();
  material["meshes"][0]["primitives"][0]["material"] = 4294967296ull;
  REQUIRE_THROWS_WITH(vt::loadGltfScene(writeQuad(dir, material)),
                      Contains("meshes[0].primitives[0].material is 4294967296, which does not fit in 32 bits"));
  auto texture = quadGltf();
  texture["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 4294967297ull}};
  REQUIRE_THROWS_WITH(vt::loadGltfScene(writeQuad(dir, texture)), Contains("baseColorTexture.index is 4294967297"));
  auto haptic = quadGltf();
  haptic["meshes"][0]["extensions"]["MPEG_haptic_material"] = {{"hapticMaterialIndex", -4294967296ll}};
  REQUIRE_THROWS_WITH(vt::loadGltfScene(writeQuad(dir, haptic)), Contains("hapticMaterialIndex is -4294967296"));
  // What nobody reads may hold any integer: others' extras and extensions, byte sizes and counts.
  auto foreign = quadGltf();
  foreign["nodes"][0]["extras"] = {{"timestamp", 1700000000000ull}};
  foreign["extensions"]["VENDOR_x"] = {{"id", 1ull << 40}};
  CHECK_NOTHROW(vt::loadGltfScene(writeQuad(dir, foreign)));
  // 40 buffers naming one 1 MiB file: each read counts (the budget is for every file together).
  std::ofstream(dir / "one.bin", std::ios::binary).write(std::string(1 << 20, '\0').data(), 1 << 20);
  auto many = quadGltf();
  many["buffers"] = nlohmann::json::array();
  for (int i = 0; i < 40; ++i) many["buffers"].push_back({{"uri", "one.bin"}, {"byteLength", 1 << 20}});
  many["buffers"][0] = {{"uri", "quad.bin"}, {"byteLength", 92}};
  CHECK(vt::loadGltfScene(writeQuad(dir, many)).objects.size() == 1);  // 39 MiB: within the budget
  // (over it: hostile.gltf_buffers_name_one_file, under a memory ceiling)
}

TEST_CASE("glTF vertex counts are held to the budget from the accessors, before any vertex is read") {
  const auto dir = vt::test::outputDir("gltf_vertex_budget");
  // One accessor of 2^23 + 1 vertices in a sparse 96 MiB file: refused without reading it.
  const std::uint64_t count = vt::budget::kSceneVertices + 1;
  {
    std::ofstream(dir / "huge.bin", std::ios::binary).put('\0');
  }
  std::filesystem::resize_file(dir / "huge.bin", count * 12);
  auto gltf = quadGltf();
  gltf["materials"][0]["extras"]["vtouching"].erase("vibration_map");
  gltf["buffers"] = {{{"uri", "huge.bin"}, {"byteLength", count * 12}}};
  gltf["bufferViews"] = {{{"buffer", 0}, {"byteLength", count * 12}}};
  gltf["accessors"] = {{{"bufferView", 0}, {"componentType", 5126}, {"count", count}, {"type", "VEC3"}}};
  gltf["meshes"][0]["primitives"][0]["attributes"] = {{"POSITION", 0}};
  gltf["meshes"][0]["primitives"][0].erase("indices");
  std::ofstream(dir / "huge.gltf") << gltf.dump();
  REQUIRE_THROWS_WITH(vt::loadGltfScene(dir / "huge.gltf"),
                      Contains("huge.gltf") && Contains("1 mesh instances hold more than 8388608 vertices"));
}

TEST_CASE("glTF: a missing buffer is named missing, not outside the scene folder") {
  const auto root = vt::test::outputDir("gltf_missing_buffer");
  std::filesystem::create_directories(root / "scene");
  auto missing = quadGltf();
  missing["buffers"][0]["uri"] = "gone.bin";
  const auto path = writeQuad(root / "scene", missing);
  REQUIRE_THROWS_WITH(vt::loadGltfScene(path), Contains("gone.bin") && Contains("not found") && !Contains("outside"));
}
