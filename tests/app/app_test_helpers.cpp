#include "app_test_helpers.hpp"

#include <fstream>
#include <sstream>

#include <catch2/catch.hpp>

#include "vt/scene/image.hpp"
#include "vt/scene/trajectory.hpp"

namespace vt::test {

std::filesystem::path writeBandDataset(const std::filesystem::path& dir, const std::string& name, int width,
                                       int height, float bandStart, float bandEnd, double mmPerPixel) {
  const auto folder = dir / name;
  std::filesystem::create_directories(folder);
  Image8 photo(width, height, 3), map(width, height, 1);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float u = (float(x) + 0.5f) / float(width);
      const bool band = u >= bandStart && u < bandEnd;
      for (int c = 0; c < 3; ++c) photo.at(x, y, c) = band ? 60 : std::uint8_t(180 + 40 * ((x / 8 + y / 8) % 2));
      map.at(x, y, 0) = band ? 230 : 20;
    }
  }
  savePng(folder / (name + ".png"), photo);
  savePng(folder / (name + "_acc.png"), map);
  std::ofstream(folder / (name + "_map.json")) << "{\"mm_per_pixel\": " << mmPerPixel << "}\n";
  return dir;
}

std::filesystem::path writeIndexSlide(const std::filesystem::path& file, glm::vec3 from, glm::vec3 to, float press_m,
                                      double seconds) {
  // Curl only the index finger a little so its tip is the hand's lowest point.
  const FingerCurls curls{0.0f, 0.1f, 0.0f, 0.0f, 0.0f};
  const HandPose model = poseHand(palmTransform({0, 0, 0}, {0, 0, 0}), curls);
  const glm::vec3 tip = model.at(HandJoint::IndexTip);
  const float radius = model.radius_m[std::size_t(HandJoint::IndexTip)];
  auto palmFor = [&](glm::vec3 p, float lift) { return p - tip + glm::vec3(0.0f, radius - press_m + lift, 0.0f); };
  std::ofstream out(file);
  out << "t_s,x_m,y_m,z_m,curl_thumb,curl_index,curl_middle,curl_ring,curl_little\n";
  auto key = [&](double t, glm::vec3 palm) {
    out << t << ',' << palm.x << ',' << palm.y << ',' << palm.z << ",0,0.1,0,0,0\n";
  };
  key(0.0, palmFor(from, 0.02f));
  key(0.2, palmFor(from, 0.0f));
  key(0.2 + seconds, palmFor(to, 0.0f));
  key(0.4 + seconds, palmFor(to, 0.02f));
  return file;
}

std::vector<TraceRow> readTraces(const std::filesystem::path& csv) {
  std::ifstream in(csv);
  REQUIRE(in);
  std::string line;
  std::getline(in, line);
  REQUIRE(line == "time_s,finger,contact,material,u,v,depth_m,map_value,intensity,across_weight");
  std::vector<TraceRow> rows;
  while (std::getline(in, line)) {
    std::stringstream s(line);
    std::string field;
    TraceRow r;
    std::getline(s, field, ',');
    r.t_s = std::stod(field);
    std::getline(s, r.finger, ',');
    std::getline(s, field, ',');
    r.contact = field == "1";
    std::getline(s, r.material, ',');
    float* values[] = {&r.u, &r.v, &r.depth_m, &r.mapValue, &r.intensity};
    for (float* v : values) {
      std::getline(s, field, ',');
      *v = std::stof(field);
    }
    rows.push_back(r);
  }
  return rows;
}

}  // namespace vt::test
