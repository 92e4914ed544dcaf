#include "vt/acquisition/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "vt/acquisition/scan.hpp"
#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/core/text_input.hpp"
#include "vt/scene/image.hpp"

namespace vt::acq {
namespace {

const char* sourceName(StatsSource s) { return s == StatsSource::Taxels ? "taxels_g" : "normalised_png"; }

ObjectStats objectStats(const std::filesystem::path& folder, const std::string& name) {
  ObjectStats row{name, StatsSource::Taxels, {}};
  const auto header = folder / (name + "_map.json");
  std::error_code ec;
  if (std::filesystem::is_regular_file(header, ec)) {
    const std::string where = header.string();
    nlohmann::json doc;
    try {
      const std::string text = readTextFile(header, "map header");
      checkJsonNesting(text, where, budget::kJsonDepth);
      doc = nlohmann::json::parse(text);
      const auto& s = doc.at("statistics");
      row.stats.scale = s.at("v_scale_g").get<double>();
      row.stats.mean = s.at("v_mean_g").get<double>();
      row.stats.std = s.at("v_std_g").get<double>();
      row.stats.min = s.at("v_min_g").get<double>();
      row.stats.max = s.at("v_max_g").get<double>();
      row.stats.count = s.at("taxels").get<std::size_t>();
      // Datasets before the noise correction have neither field.
      if (const auto n = doc.find("noise"); n != doc.end() && n->contains("sigma_g") && n->at("sigma_g").is_number()) {
        row.noise_g = n->at("sigma_g").get<double>();
      }
      if (const auto c = doc.find("statistics_noise_corrected"); c != doc.end() && c->is_object()) {
        row.corrected = TaxelStats{c->at("v_scale_g").get<double>(), c->at("v_mean_g").get<double>(),
                                   c->at("v_std_g").get<double>(),   c->at("v_min_g").get<double>(),
                                   c->at("v_max_g").get<double>(),   c->at("taxels").get<std::size_t>()};
      }
    } catch (const nlohmann::json::exception& e) {
      fail(where, ": bad map header (field 'statistics'): ", e.what());
    }
    return row;
  }
  // Published folders only hold the normalised map: statistics of its covered (non-zero)
  // pixels, unitless and area-weighted, labelled as such.
  row.source = StatsSource::NormalisedPng;
  const Image16 map = loadImage16(folder / (name + "_acc.png"), 1);
  std::vector<double> values;
  values.reserve(map.pixels.size());
  for (std::uint16_t p : map.pixels) {
    if (p > 0) values.push_back(p / 65535.0);
  }
  row.stats = computeStats(values);
  return row;
}

}  // namespace

TaxelStats computeStats(std::span<const double> values) noexcept {
  TaxelStats s;
  if (values.empty()) return s;
  s.count = values.size();
  s.min = *std::min_element(values.begin(), values.end());
  s.max = *std::max_element(values.begin(), values.end());
  s.scale = s.max - s.min;
  double sum = 0;
  for (double v : values) sum += v;
  s.mean = sum / double(values.size());
  double sq = 0;
  for (double v : values) sq += (v - s.mean) * (v - s.mean);
  s.std = std::sqrt(sq / double(values.size()));
  return s;
}

std::vector<ObjectStats> datasetStats(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) fail("dataset directory '", dir.string(), "': not found");
  std::vector<ObjectStats> rows;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    if (!entry.is_directory()) continue;
    const std::string name = entry.path().filename().string();
    if (std::filesystem::is_regular_file(entry.path() / (name + "_acc.png"), ec)) rows.push_back(objectStats(entry.path(), name));
  }
  if (rows.empty()) fail("dataset directory '", dir.string(), "': no object folders NAME/NAME_acc.png found");
  std::sort(rows.begin(), rows.end(), [](const ObjectStats& a, const ObjectStats& b) { return a.name < b.name; });
  return rows;
}

std::string statsCsv(std::span<const ObjectStats> rows) {
  std::string out = "name,source,v_scale,v_mean,v_std,count,noise_g,v_scale_corrected,v_mean_corrected,v_std_corrected\n";
  char line[512];
  for (const ObjectStats& r : rows) {
    std::snprintf(line, sizeof line, "%s,%s,%.6f,%.6f,%.6f,%zu,", r.name.c_str(), sourceName(r.source), r.stats.scale,
                  r.stats.mean, r.stats.std, r.stats.count);
    out += line;
    if (r.noise_g) std::snprintf(line, sizeof line, "%.6f", *r.noise_g), out += line;
    if (r.corrected) {
      std::snprintf(line, sizeof line, ",%.6f,%.6f,%.6f\n", r.corrected->scale, r.corrected->mean, r.corrected->std);
      out += line;
    } else {
      out += ",,,\n";
    }
  }
  return out;
}

std::string statsJson(std::span<const ObjectStats> rows) {
  nlohmann::json doc = nlohmann::json::array();
  for (const ObjectStats& r : rows) {
    doc.push_back({{"name", r.name},
                   {"source", sourceName(r.source)},
                   {"unit", r.source == StatsSource::Taxels ? "g" : "normalised (0..1)"},
                   {"v_scale", r.stats.scale},
                   {"v_mean", r.stats.mean},
                   {"v_std", r.stats.std},
                   {"count", r.stats.count},
                   {"noise_g", r.noise_g ? nlohmann::json(*r.noise_g) : nlohmann::json(nullptr)},
                   {"noise_corrected", r.corrected ? nlohmann::json{{"v_scale", r.corrected->scale},
                                                                    {"v_mean", r.corrected->mean},
                                                                    {"v_std", r.corrected->std}}
                                                   : nlohmann::json(nullptr)}});
  }
  return doc.dump(2) + "\n";
}

std::string statsTable(std::span<const ObjectStats> rows) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line, "%-24s %9s %9s %9s  %-16s %8s  %s\n", "object", "V_scale", "V_mean", "V_std", "source",
                "noise", "noise-corrected V_scale / V_mean / V_std");
  out += line;
  bool anyNormalised = false;
  for (const ObjectStats& r : rows) {
    const bool norm = r.source == StatsSource::NormalisedPng;
    anyNormalised |= norm;
    std::snprintf(line, sizeof line, "%-24s %9.3f %9.3f %9.3f  %-16s", r.name.c_str(), r.stats.scale, r.stats.mean,
                  r.stats.std, norm ? "normalised map*" : "taxels (g)");
    out += line;
    if (r.noise_g) std::snprintf(line, sizeof line, " %6.4f g", *r.noise_g);
    else std::snprintf(line, sizeof line, " %8s", "-");
    out += line;
    if (r.corrected) std::snprintf(line, sizeof line, "  %.3f / %.3f / %.3f\n", r.corrected->scale, r.corrected->mean, r.corrected->std);
    else std::snprintf(line, sizeof line, "  -\n");
    out += line;
  }
  if (anyNormalised) {
    out += "* only the min-max normalised NAME_acc.png is present: statistics of its non-zero pixels, unitless,\n"
           "  area-weighted; not comparable with taxel values in g (the paper's Table I).\n";
  }
  return out;
}

}  // namespace vt::acq
