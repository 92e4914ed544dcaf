// Scene export round trip through the app's scene source, and the intensity mode in the traces.
#include <fstream>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "modes/scene_source.hpp"
#include "modes/trajectory_run.hpp"
#include "test_support.hpp"
#include "vt/scene/gltf_writer.hpp"

using namespace vt;
using namespace vt::test;

namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

TEST_CASE("The example slide over the exported default dataset gives the same traces", "[app][export]") {
  const auto out = outputDir("app_export_slide");
  app::TrajectoryRunOptions options;
  options.trajectory = app::defaultTrajectory();
  REQUIRE(!options.trajectory.empty());
  options.fps = 0.0;
  options.scene.dataset = (sourceDir() / "assets/dataset").string();
  const app::LoadedScene dataset = app::loadScene(options.scene);
  saveGltfScene(*dataset.scene, out / "scene.glb", false);
  options.outDir = out / "dataset";
  const auto a = app::runTrajectory(options);

  options.scene = {};
  options.scene.gltf = (out / "scene.glb").string();
  options.outDir = out / "glb";
  const auto b = app::runTrajectory(options);
  CHECK(b.ticks == a.ticks);
  CHECK(a.peakIntensity > 0.05f);
  const std::string tracesA = slurp(a.tracesCsv);
  CHECK(tracesA.size() > 10000);
  CHECK(tracesA == slurp(b.tracesCsv));

  // Both runs say which intensity mode they measured.
  const auto about = nlohmann::json::parse(slurp(out / "glb/traces.json"));
  CHECK(about["intensity"].get<std::string>().rfind("absolute", 0) == 0);
  CHECK(about["scene"].get<std::string>().find("intensity absolute") != std::string::npos);
}

TEST_CASE("Scene options carry --intensity and --gains through a recording's scene line", "[app][export]") {
  app::SceneOptions options;
  options.dataset = "some dir";
  options.normalised = true;
  options.gains = "my gains.csv";
  const app::SceneOptions back = app::decodeSceneOptions(app::encodeSceneOptions(options), "test");
  CHECK(back.dataset == options.dataset);
  CHECK(back.normalised);
  CHECK(back.gains == options.gains);
  // Recordings from before --intensity replay as they were made: normalised.
  CHECK(app::decodeSceneOptions("mm_per_pixel=0 builtin=0 gltf=0: dataset=3:abc", "old").normalised);
}
