#include <catch2/catch.hpp>

#include <fstream>

#include <nlohmann/json.hpp>

#include "json_file.hpp"
#include "test_support.hpp"
#include "vt/core/error.hpp"
#include "vt/scene/gltf_writer.hpp"
#include "vt/scene/loaders.hpp"

using Catch::Matchers::Contains;

namespace {

// Two small objects; "beta" carries acquisition metadata (normalisation spans 0.2 g).
std::filesystem::path smallDataset(const std::filesystem::path& dir, bool metadata) {
  for (const char* name : {"alpha", "beta"}) {
    std::filesystem::create_directories(dir / name);
    vt::savePng(dir / name / (std::string(name) + ".png"), vt::Image8(40, 20, 3));
    vt::Image16 acc(40, 20, 1);
    for (int x = 0; x < 40; ++x) acc.at(x, 7) = std::uint16_t(1000 * x + 3);
    vt::savePng16(dir / name / (std::string(name) + "_acc.png"), acc);
  }
  if (metadata) {
    std::ofstream(dir / "alpha" / "alpha_map.json") << R"({"mm_per_pixel": 0.3, "normalisation": {"min_g": 0.1, "max_g": 0.9}})";
    std::ofstream(dir / "beta" / "beta_map.json") << R"({"mm_per_pixel": [0.5, 0.5], "normalisation": {"min_g": 0.0, "max_g": 0.2}})";
  }
  return dir;
}

}  // namespace

TEST_CASE("A two-direction dataset keeps its across map and scan direction through glTF export", "[gltf][export]") {
  const auto dir = smallDataset(vt::test::outputDir("gltf_export_two_directions") / "data", true);
  vt::Image16 across(40, 20, 1);
  for (int y = 0; y < 20; ++y) across.at(5, y) = std::uint16_t(2000 * y + 1);
  vt::savePng16(dir / "alpha" / "alpha_acc_across.png", across);
  std::ofstream(dir / "alpha" / "alpha_map.json")
      << R"({"mm_per_pixel": 0.3, "normalisation": {"min_g": 0.1, "max_g": 0.9}, "scan_direction_uv": [0.6, 0.8]})";
  const vt::Scene original = vt::loadDatasetScene(dir);
  REQUIRE(original.materials[0].vibrationMapAcross >= 0);
  const auto out = dir.parent_path() / "scene.glb";
  vt::saveGltfScene(original, out, true);
  const vt::Scene loaded = vt::loadGltfScene(out);
  CHECK(vt::tactileDigest(loaded) == vt::tactileDigest(original));
  REQUIRE(loaded.materials[0].vibrationMapAcross >= 0);
  CHECK(loaded.vibrationMaps[std::size_t(loaded.materials[0].vibrationMapAcross)].pixels ==
        original.vibrationMaps[std::size_t(original.materials[0].vibrationMapAcross)].pixels);
  CHECK(loaded.materials[0].scanDirectionUv.x == Approx(0.6f));
  CHECK(loaded.materials[0].scanDirectionUv.y == Approx(0.8f));
}

TEST_CASE("The default dataset exported as .glb and .gltf loads back with the same tactile digest", "[gltf][export]") {
  const auto out = vt::test::outputDir("gltf_export_roundtrip");
  const vt::Scene original = vt::loadDatasetScene(vt::test::sourceDir() / "assets/dataset");
  REQUIRE(original.vibrationMaps.size() == 8);
  for (const char* file : {"scene.glb", "scene.gltf"}) {
    vt::saveGltfScene(original, out / file, false);
    // Every file of an export is refused when it exists, unless replaced on purpose.
    REQUIRE_THROWS_WITH(vt::saveGltfScene(original, out / file, false), Contains("already exists (use --force"));
    vt::saveGltfScene(original, out / file, true);
    const vt::Scene loaded = vt::loadGltfScene(out / file);
    INFO(file);
    CHECK(vt::tactileDigest(loaded) == vt::tactileDigest(original));
    REQUIRE(loaded.objects.size() == original.objects.size());
    CHECK(loaded.objects[3].name == original.objects[3].name);
    CHECK(loaded.textures[2].pixels == original.textures[2].pixels);
    CHECK(loaded.intensity == original.intensity);
    CHECK(loaded.unused.empty());
  }
  // The standard extension carries the map: no extras-based vibration_map in the file.
  const auto doc = readJson(out / "scene.gltf");
  CHECK(doc["extensionsUsed"] == nlohmann::json::array({"MPEG_haptic_material"}));
  CHECK(doc["extensions"]["MPEG_haptic_material"]["materials"].size() == 8);
  CHECK(doc["meshes"][0]["extensions"]["MPEG_haptic_material"]["hapticMaterialIndex"] == 0);
  CHECK_FALSE(doc["materials"][0].contains("extras"));
}

TEST_CASE("MPEG_haptic_material: other haptic maps are reported, 'vibration' is the fallback", "[gltf][export]") {
  const auto out = vt::test::outputDir("gltf_haptic_material");
  const vt::Scene original = vt::loadDatasetScene(smallDataset(out / "dataset", false));
  vt::saveGltfScene(original, out / "scene.gltf", false);
  auto doc = readJson(out / "scene.gltf");
  auto& haptic = doc["extensions"]["MPEG_haptic_material"]["materials"];
  haptic[0]["stiffness"] = {{{"texture", {{"index", 0}}}, {"type", "Low_Resolution"}}};
  haptic[1]["vibration"] = haptic[1]["vibrotactileTexture"];
  haptic[1].erase("vibrotactileTexture");
  haptic[1]["vibration"][0]["type"] = "Low_Resolution";
  writeJson(out / "edited.gltf", doc);
  const vt::Scene edited = vt::loadGltfScene(out / "edited.gltf");
  CHECK(vt::tactileDigest(edited) == vt::tactileDigest(original));
  REQUIRE(edited.unused.size() == 1);
  CHECK_THAT(edited.unused[0], Contains("alpha") && Contains("stiffness"));

  auto badIndex = readJson(out / "scene.gltf");
  badIndex["meshes"][0]["extensions"]["MPEG_haptic_material"]["hapticMaterialIndex"] = 7;
  writeJson(out / "bad_index.gltf", badIndex);
  REQUIRE_THROWS_WITH(vt::loadGltfScene(out / "bad_index.gltf"),
                      Contains("bad_index.gltf") && Contains("hapticMaterialIndex 7 out of range"));
  auto badType = readJson(out / "scene.gltf");
  badType["extensions"]["MPEG_haptic_material"]["materials"][0]["vibrotactileTexture"][0]["type"] = "Huge";
  writeJson(out / "bad_type.gltf", badType);
  REQUIRE_THROWS_WITH(vt::loadGltfScene(out / "bad_type.gltf"), Contains("vibrotactileTexture[0].type 'Huge'"));
  auto badGain = readJson(out / "scene.gltf");
  badGain["extensions"]["MPEG_haptic_material"]["materials"][1]["extras"]["vtouching"]["gain"] = -1;
  writeJson(out / "bad_gain.gltf", badGain);
  REQUIRE_THROWS_WITH(vt::loadGltfScene(out / "bad_gain.gltf"), Contains("materials[1].extras.vtouching.gain"));
  REQUIRE_THROWS_WITH(vt::saveGltfScene(original, out / "scene.obj", false), Contains(".glb or .gltf"));
}

TEST_CASE("Absolute intensity scales each object's gain by its physical map span", "[dataset][intensity]") {
  const auto dir = smallDataset(vt::test::outputDir("dataset_intensity"), true);
  const vt::Scene absolute = vt::loadDatasetScene(dir);
  CHECK(absolute.materials[0].tactileGain == Approx(0.5f));          // alpha spans 0.8 g, the widest
  CHECK(absolute.materials[1].tactileGain == Approx(0.5f * 0.25f));  // beta spans 0.2 g
  CHECK_THAT(absolute.intensity, Contains("absolute"));
  vt::DatasetSceneOptions normalised;
  normalised.intensity = vt::IntensityMode::Normalised;
  const vt::Scene plain = vt::loadDatasetScene(dir, normalised);
  CHECK(plain.materials[1].tactileGain == Approx(0.5f));
  CHECK(plain.intensity == "normalised");

  std::ofstream(dir / "gains.csv") << "name,gain\n# louder beta\nbeta,3\n";
  normalised.gainsFile = dir / "gains.csv";
  const vt::Scene gained = vt::loadDatasetScene(dir, normalised);
  CHECK(gained.materials[0].tactileGain == Approx(0.5f));
  CHECK(gained.materials[1].tactileGain == Approx(1.5f));
  CHECK_THAT(gained.intensity, Contains("gains gains.csv"));

  std::ofstream(dir / "typo.csv") << "gamma,2\n";
  normalised.gainsFile = dir / "typo.csv";
  REQUIRE_THROWS_WITH(vt::loadDatasetScene(dir, normalised), Contains("typo.csv") && Contains("no object 'gamma'"));
  std::ofstream(dir / "bad.csv") << "beta,loud\n";
  REQUIRE_THROWS_WITH(vt::loadGainTable(dir / "bad.csv"), Contains("bad.csv' line 1") && Contains("[0, 20]"));
  std::filesystem::create_directories(dir / "folder.csv");  // an ifstream would read it as an empty table
  REQUIRE_THROWS_WITH(vt::loadGainTable(dir / "folder.csv"), Contains("gain table '") && Contains("folder.csv': is a folder"));

  // Without metadata the absolute mode says it could not apply.
  const vt::Scene bare = vt::loadDatasetScene(smallDataset(vt::test::outputDir("dataset_intensity_bare"), false));
  CHECK_THAT(bare.intensity, Contains("no V_scale"));
  CHECK(bare.materials[1].tactileGain == Approx(0.5f));
}
