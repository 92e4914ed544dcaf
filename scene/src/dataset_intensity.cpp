#include "dataset_intensity.hpp"

#include <cmath>
#include <sstream>

#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/core/text_input.hpp"
#include "vt/core/file_io.hpp"
#include "vt/core/log.hpp"

namespace vt {
namespace {

// The physical span (g) behind a map's 0..1: the peak of a two-direction object (its maps are
// loaded as V / peak), else max_g - min_g of its normalisation, else the statistics' V_scale; 0
// when NAME_map.json says none of them.
double mapSpan_g(const nlohmann::json& meta) {
  if (!meta.is_object()) return 0.0;
  if (const double peak = twoDirectionPeak_g(meta); peak > 0.0) return peak;
  const auto number = [](const nlohmann::json& j, const char* a, const char* b) {
    const auto outer = j.find(a);
    if (outer == j.end() || !outer->is_object()) return std::nan("");
    const auto inner = outer->find(b);
    return inner != outer->end() && inner->is_number() ? inner->get<double>() : std::nan("");
  };
  const double span = number(meta, "normalisation", "max_g") - number(meta, "normalisation", "min_g");
  if (span > 0.0) return span;
  const double scale = number(meta, "statistics", "v_scale_g");
  return scale > 0.0 ? scale : 0.0;
}

}  // namespace

std::optional<std::array<double, 2>> pngRange_g(const nlohmann::json& meta, bool across) {
  if (!meta.is_object()) return std::nullopt;
  const nlohmann::json* holder = &meta;
  if (across) {
    const auto it = meta.find("across");
    if (it == meta.end() || !it->is_object()) return std::nullopt;
    holder = &*it;
  }
  const auto n = holder->find("normalisation");
  // Datasets before the across map had its own range recorded a string here: no range.
  if (n == holder->end() || !n->is_object()) return std::nullopt;
  const auto lo = n->find("min_g"), hi = n->find("max_g");
  if (lo == n->end() || hi == n->end() || !lo->is_number() || !hi->is_number()) return std::nullopt;
  const std::array<double, 2> range{lo->get<double>(), hi->get<double>()};
  if (!(std::isfinite(range[0]) && std::isfinite(range[1]) && range[0] >= 0.0 && range[1] >= range[0])) return std::nullopt;
  return range;
}

double twoDirectionPeak_g(const nlohmann::json& meta) {
  const auto main = pngRange_g(meta, false), across = pngRange_g(meta, true);
  if (!main || !across) return 0.0;
  const double peak = std::max((*main)[1], (*across)[1]);
  return peak > 0.0 ? peak : 0.0;
}

std::map<std::string, float> loadGainTable(const std::filesystem::path& file) {
  const std::string source = "gain table '" + file.string() + "'";
  std::istringstream in(readInputText(file, "gain table", budget::kTextFileBytes));
  std::map<std::string, float> gains;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#' || (number == 1 && line == "name,gain")) continue;
    const auto comma = line.find(',');
    if (comma == std::string::npos || comma == 0) fail(source, " line ", number, ": expected NAME,GAIN");
    const std::string name = line.substr(0, comma);
    char* end = nullptr;
    const double gain = std::strtod(line.c_str() + comma + 1, &end);
    if (end == line.c_str() + comma + 1 || *end != '\0' || !(gain >= 0.0 && gain <= 20.0)) {
      fail(source, " line ", number, ": gain of '", name, "' must be a number in [0, 20]");
    }
    if (!gains.emplace(name, float(gain)).second) fail(source, " line ", number, ": '", name, "' listed twice");
  }
  return gains;
}

void applyDatasetIntensity(Scene& scene, const std::vector<std::string>& names,
                           const std::vector<nlohmann::json>& metas, const DatasetSceneOptions& options) {
  std::string mode = "normalised";
  if (options.intensity == IntensityMode::Absolute) {
    std::vector<double> spans;
    double widest = 0.0;
    for (const nlohmann::json& meta : metas) widest = std::max(widest, spans.emplace_back(mapSpan_g(meta)));
    int without = 0;
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (spans[i] > 0.0) scene.materials[i].tactileGain *= float(spans[i] / widest);
      else ++without;
    }
    if (widest <= 0.0) mode = "normalised (no V_scale in the dataset; --gains FILE sets per-object gains)";
    else mode = str("absolute (V_scale from NAME_map.json", without ? str(", ", without, " objects without it normalised") : "", ")");
  }
  if (!options.gainsFile.empty()) {
    const auto gains = loadGainTable(options.gainsFile);
    for (const auto& [name, gain] : gains) {
      const auto it = std::find(names.begin(), names.end(), name);
      if (it == names.end()) fail("gain table '", options.gainsFile.string(), "': no object '", name, "' in the dataset");
      scene.materials[std::size_t(it - names.begin())].tactileGain *= gain;
    }
    for (const std::string& name : names) {
      if (!gains.count(name)) log::info("gain table: '", name, "' not listed, gain 1");
    }
    mode += " x gains " + options.gainsFile.filename().string();
  }
  for (const Material& m : scene.materials) {
    if (m.tactileGain > 10.0f) fail("dataset: material '", m.name, "' tactile gain ", m.tactileGain, " above 10 after --gains");
  }
  scene.intensity = mode;
}

}  // namespace vt
