#pragma once
// Shared by the app tests: synthetic datasets, straight-slide trajectories and trace parsing.
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "vt/scene/hand.hpp"

namespace vt::test {

/// Writes DIR/NAME/NAME.png (grey photo) and NAME_acc.png (dark, with a bright band of columns
/// [bandStart, bandEnd) of the width), plus NAME_map.json with mm_per_pixel. Returns DIR.
std::filesystem::path writeBandDataset(const std::filesystem::path& dir, const std::string& name, int width,
                                       int height, float bandStart, float bandEnd, double mmPerPixel);

/// A CSV trajectory sliding the index fingertip (others straight, above it) from `from` to `to`
/// (world, metres) pressing `press_m` into a surface at height surface_y over `seconds`.
std::filesystem::path writeIndexSlide(const std::filesystem::path& file, glm::vec3 from, glm::vec3 to, float press_m,
                                      double seconds);

/// One row of traces.csv.
struct TraceRow {
  double t_s = 0;
  std::string finger, material;
  bool contact = false;
  float u = 0, v = 0, depth_m = 0, mapValue = 0, intensity = 0;
};
std::vector<TraceRow> readTraces(const std::filesystem::path& csv);

}  // namespace vt::test
