#include "vt/scene/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/core/text_input.hpp"
#include "vt/core/file_io.hpp"

namespace vt {
namespace {

glm::quat rotationFromEuler(glm::vec3 deg) {
  const glm::vec3 r = glm::radians(deg);
  return glm::angleAxis(r.x, glm::vec3(0, 1, 0)) * glm::angleAxis(r.y, glm::vec3(1, 0, 0)) *
         glm::angleAxis(r.z, glm::vec3(0, 0, 1));
}

void checkKeys(const Trajectory& trajectory, const std::string& source) {
  if (trajectory.keys.empty()) fail(source, ": the trajectory has no samples");
  for (std::size_t i = 0; i < trajectory.keys.size(); ++i) {
    const TrajectoryKey& k = trajectory.keys[i];
    const bool finite = std::isfinite(k.t_s) && std::isfinite(k.palm_m.x) && std::isfinite(k.palm_m.y) &&
                        std::isfinite(k.palm_m.z) && std::isfinite(k.rotation_deg.x) &&
                        std::isfinite(k.rotation_deg.y) && std::isfinite(k.rotation_deg.z);
    if (!finite) fail(source, ": sample ", i + 1, " has a NaN or infinite value");
    if (!(std::abs(k.t_s) <= budget::kStampTime_s)) {
      fail(source, ": sample ", i + 1, " time ", k.t_s, " s is beyond +-2^61 ns (73 years; docs/RELIABILITY.md)");
    }
    for (float c : k.curls) {
      if (!(c >= 0.0f && c <= 1.0f)) fail(source, ": sample ", i + 1, " has a finger curl outside 0..1");
    }
    if (i > 0 && !(k.t_s > trajectory.keys[i - 1].t_s)) {
      fail(source, ": sample ", i + 1, " time ", k.t_s, " s is not after the previous sample's");
    }
  }
  if (trajectory.duration_s() > budget::kTrajectoryDuration_s) {
    fail(source, ": lasts ", trajectory.duration_s(), " s, over the limit of ", budget::kTrajectoryDuration_s,
         " s (docs/RELIABILITY.md)");
  }
}

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream stream(line);
  std::string cell;
  while (std::getline(stream, cell, ',')) {
    cell.erase(0, cell.find_first_not_of(" \t\r"));
    cell.erase(cell.find_last_not_of(" \t\r") + 1);
    cells.push_back(cell);
  }
  return cells;
}

}  // namespace

glm::mat4 palmTransform(glm::vec3 palm_m, glm::vec3 rotation_deg) {
  return glm::translate(glm::mat4(1.0f), palm_m) * glm::mat4_cast(rotationFromEuler(rotation_deg));
}

HandPose Trajectory::poseAt(double t_s) const {
  VT_ASSERT(!keys.empty());
  // Clamped to the keys once, for the pose and its stamp alike (NaN: the first key), so any
  // double a caller passes gives a finite pose and a stamp that fits 64-bit nanoseconds.
  const double t = t_s > keys.back().t_s ? keys.back().t_s : t_s >= keys.front().t_s ? t_s : keys.front().t_s;
  // Keys increase in time (checkKeys): a binary search, so a long file is not a quadratic run
  // (2.5 M keys in 60 MB, within the text budget, took hours scanned from the start each tick).
  const auto after = std::upper_bound(keys.begin() + 1, keys.end(), t,
                                      [](double time, const TrajectoryKey& key) { return time < key.t_s; });
  const std::size_t i = std::size_t(after - keys.begin()) - 1;
  const TrajectoryKey& a = keys[i];
  const TrajectoryKey& b = keys[std::min(i + 1, keys.size() - 1)];
  const float f = b.t_s > a.t_s ? float(std::clamp((t - a.t_s) / (b.t_s - a.t_s), 0.0, 1.0)) : 0.0f;
  const glm::vec3 palm = glm::mix(a.palm_m, b.palm_m, f);
  const glm::quat q = glm::slerp(rotationFromEuler(a.rotation_deg), rotationFromEuler(b.rotation_deg), f);
  FingerCurls curls{};
  for (std::size_t c = 0; c < curls.size(); ++c) curls[c] = a.curls[c] + (b.curls[c] - a.curls[c]) * f;
  return poseHand(glm::translate(glm::mat4(1.0f), palm) * glm::mat4_cast(q), curls, leftHand, std::int64_t(t * 1e9));
}

Trajectory parseTrajectoryCsv(const std::string& text, const std::string& source) {
  std::string line;
  std::vector<std::string> header;
  Trajectory trajectory;
  // Peak memory: the text and one key per row (no copy of the text, no doubling of the keys).
  trajectory.keys.reserve(std::size_t(std::count(text.begin(), text.end(), '\n')) + 1);
  int lineNumber = 0;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    line.assign(text, at, end - at);
    at = end + 1;
    ++lineNumber;
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> cells = splitCsv(line);
    if (header.empty()) {
      header = cells;
      for (const char* required : {"t_s", "x_m", "y_m", "z_m"}) {
        if (std::find(header.begin(), header.end(), required) == header.end()) {
          fail(source, ": header line lacks column '", required, "' (expected t_s,x_m,y_m,z_m[,yaw_deg,pitch_deg,",
               "roll_deg][,curl_thumb,curl_index,curl_middle,curl_ring,curl_little])");
        }
      }
      continue;
    }
    if (cells.size() != header.size()) {
      fail(source, ": line ", lineNumber, " has ", cells.size(), " values, the header has ", header.size());
    }
    TrajectoryKey key;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      double v = 0.0;
      try {
        std::size_t used = 0;
        v = std::stod(cells[c], &used);
        if (used != cells[c].size()) throw std::invalid_argument("trailing");
      } catch (const std::exception&) {
        fail(source, ": line ", lineNumber, " column '", header[c], "': '", cells[c], "' is not a number");
      }
      static const std::pair<const char*, int> kColumns[] = {
          {"t_s", -1}, {"x_m", 0}, {"y_m", 1}, {"z_m", 2}, {"yaw_deg", 3}, {"pitch_deg", 4}, {"roll_deg", 5},
          {"curl_thumb", 6}, {"curl_index", 7}, {"curl_middle", 8}, {"curl_ring", 9}, {"curl_little", 10}};
      bool known = false;
      for (const auto& [name, slot] : kColumns) {
        if (header[c] != name) continue;
        known = true;
        if (slot == -1) key.t_s = v;
        else if (slot < 3) key.palm_m[slot] = float(v);
        else if (slot < 6) key.rotation_deg[slot - 3] = float(v);
        else key.curls[std::size_t(slot - 6)] = float(v);
      }
      if (!known) fail(source, ": unknown column '", header[c], "'");
    }
    trajectory.keys.push_back(key);
  }
  checkKeys(trajectory, source);
  return trajectory;
}

Trajectory parseTrajectoryJson(const std::string& text, const std::string& source) {
  checkJsonNesting(text, source, budget::kJsonDepth);
  const nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
  if (doc.is_discarded()) fail(source, ": not valid JSON");
  if (!doc.is_object() || !doc.contains("samples") || !doc["samples"].is_array()) {
    fail(source, ": expected an object with a 'samples' array");
  }
  Trajectory trajectory;
  if (doc.contains("hand")) {
    if (doc["hand"] != "left" && doc["hand"] != "right") fail(source, ": 'hand' must be \"left\" or \"right\"");
    trajectory.leftHand = doc["hand"] == "left";
  }
  std::size_t index = 0;
  for (const auto& s : doc["samples"]) {
    ++index;
    auto numbers = [&](const char* key, std::size_t count, float* out, bool required) {
      if (!s.contains(key)) {
        if (required) fail(source, ": sample ", index, " lacks '", key, "'");
        return;
      }
      const auto& v = s[key];
      if (!v.is_array() || v.size() != count) fail(source, ": sample ", index, " '", key, "' must be ", count, " numbers");
      for (std::size_t i = 0; i < count; ++i) {
        if (!v[i].is_number()) fail(source, ": sample ", index, " '", key, "' must be ", count, " numbers");
        out[i] = v[i].get<float>();
      }
    };
    if (!s.is_object() || !s.contains("t_s") || !s["t_s"].is_number()) {
      fail(source, ": sample ", index, " needs a numeric 't_s'");
    }
    TrajectoryKey key;
    key.t_s = s["t_s"].get<double>();
    numbers("palm_m", 3, &key.palm_m.x, true);
    numbers("rotation_deg", 3, &key.rotation_deg.x, false);
    numbers("curls", 5, key.curls.data(), false);
    trajectory.keys.push_back(key);
  }
  checkKeys(trajectory, source);
  return trajectory;
}

Trajectory loadTrajectory(const std::filesystem::path& path) {
  const std::string source = "trajectory '" + path.string() + "'";
  const std::string text = readInputText(path, "trajectory", budget::kTextFileBytes);
  if (path.extension() == ".json") return parseTrajectoryJson(text, source);
  if (path.extension() == ".csv") return parseTrajectoryCsv(text, source);
  fail(source, ": unknown extension (expected .json or .csv)");
}

}  // namespace vt
