// Writes one object in the published Pixel2Taxel layout plus our float map, header,
// preview and calibration report (docs/scan-format.md, "Output").
#include <algorithm>
#include <bit>

#include <nlohmann/json.hpp>

#include "vt/acquisition/pipeline.hpp"
#include "vt/acquisition/waveforms.hpp"
#include "vt/core/error.hpp"
#include "vt/core/output_file.hpp"
#include "parallel.hpp"

namespace vt::acq {
namespace {

Image8 makePreview(const Image8& photo, const TaxelRaster& map, const ImageF& normalised) {
  Image8 preview(photo.width, photo.height, 3);
  for (int y = 0; y < photo.height; ++y) {
    for (int x = 0; x < photo.width; ++x) {
      const bool covered = map.coverage.at(x, y) != 0;
      const auto heat = heatColour(normalised.at(x, y));
      for (int c = 0; c < 3; ++c) {
        const float p = photo.at(x, y, c);
        preview.at(x, y, c) = std::uint8_t(covered ? 0.35f * p + 0.65f * heat[std::size_t(c)] + 0.5f : p);
      }
    }
  }
  return preview;
}

// The map as a 16-bit PNG: (V - lo) / (hi - lo), clamped, 0 where uncovered.
void saveMapPng(const std::filesystem::path& path, const TaxelRaster& map, float lo, float hi) {
  Image16 acc(map.value_g.width, map.value_g.height, 1);
  const float range = hi > lo ? hi - lo : 1.0f;
  for (std::size_t i = 0; i < acc.pixels.size(); ++i) {
    if (!map.coverage.pixels[i]) continue;
    const float t = std::clamp((map.value_g.pixels[i] - lo) / range, 0.0f, 1.0f);
    acc.pixels[i] = std::uint16_t(t * 65535.0f + 0.5f);
  }
  savePng16(path, acc);
}

void saveFloatMap(const std::filesystem::path& path, const TaxelRaster& map) {
  writeFileAtomically(path, std::string_view(reinterpret_cast<const char*>(map.value_g.pixels.data()),
                                             map.value_g.pixels.size() * sizeof(float)));
}

nlohmann::json statsJson(const TaxelStats& s, std::size_t taxels, const char* source = "taxel values before normalisation") {
  return {{"v_scale_g", s.scale}, {"v_mean_g", s.mean}, {"v_std_g", s.std}, {"v_min_g", s.min},
          {"v_max_g", s.max},     {"taxels", taxels},  {"source", source}};
}

// The noise-corrected statistics beside the raw ones: null when the noise floor is unknown.
nlohmann::json correctedJson(const NoiseFloor& noise, const TaxelStats& s, std::size_t taxels) {
  if (!noise.known) return nullptr;
  return statsJson(s, taxels, "taxel values less the accelerometer noise's share (docs/scan-format.md, \"Sensor noise\")");
}

// The smallest and largest value over a raster's covered pixels, and how many are covered.
struct CoveredRange {
  float lo = 0, hi = 0;
  std::size_t covered = 0;
};

CoveredRange coveredRange(const TaxelRaster& map) {
  CoveredRange r;
  for (std::size_t i = 0; i < map.coverage.pixels.size(); ++i) {
    if (!map.coverage.pixels[i]) continue;
    const float v = map.value_g.pixels[i];
    r.lo = r.covered ? std::min(r.lo, v) : v;
    r.hi = r.covered ? std::max(r.hi, v) : v;
    ++r.covered;
  }
  return r;
}

nlohmann::json normalisationJson(const CoveredRange& range) {
  return {{"min_g", range.lo}, {"max_g", range.hi}, {"formula", "png = (V - min_g) / (max_g - min_g)"}};
}

std::size_t taxelCount(const std::vector<LineResult>& lines) {
  std::size_t n = 0;
  for (const LineResult& line : lines) n += line.taxels.size();
  return n;
}

}  // namespace

void writeDataset(const AcquireResult& r, const std::filesystem::path& outDir, bool writeFloatMap, bool replace,
                  const WaveformGrid* waveforms) {
  static_assert(std::endian::native == std::endian::little, "the .f32 format is little-endian");
  const std::string& name = r.config.name;
  // The object is built whole in a hidden folder and moved into place: a failure (a full disk)
  // leaves the previous object as it was, and a replaced object keeps no stale files.
  StagedFolder staged(outDir / name, replace);
  const auto& dir = staged.dir();

  const ImageF normalised = normaliseMap(r.map);
  Image16 acc(normalised.width, normalised.height, 1);
  for (std::size_t i = 0; i < acc.pixels.size(); ++i) acc.pixels[i] = std::uint16_t(normalised.pixels[i] * 65535.0f + 0.5f);
  const Image8 preview = makePreview(r.photo, r.map, normalised);
  // Deflating the three PNGs and writing the waveforms are most of the writing: one per worker.
  detail::parallelFor(
      waveforms ? 4 : 3, r.jobs,
      [&](std::size_t i) {
        if (i == 0) savePng(dir / (name + ".png"), r.photo);
        if (i == 1 && r.authorsMap) savePng(dir / (name + "_acc.png"), *r.authorsMap);
        if (i == 1 && !r.authorsMap) savePng16(dir / (name + "_acc.png"), acc);
        if (i == 2) savePng(dir / (name + "_preview.png"), preview);
        if (i == 3) writeWaveforms(*waveforms, dir / "waveforms");
      },
      [](std::size_t) {});
  writeFileAtomically(dir / (name + "_calibration.json"), calibrationReportJson(r.calibration, r.calibrationPoints));

  const CoveredRange range = coveredRange(r.map);
  if (writeFloatMap) saveFloatMap(dir / (name + "_map.f32"), r.map);
  const std::size_t taxels = taxelCount(r.lines);
  nlohmann::json doc;
  doc["name"] = name;
  doc["width"] = r.photo.width;
  doc["height"] = r.photo.height;
  doc["photo"] = name + ".png";
  doc["map_png"] = name + "_acc.png";
  doc["map_png_bits"] = r.authorsMap ? 8 : 16;
  doc["float_map"] = writeFloatMap ? nlohmann::json(name + "_map.f32") : nlohmann::json(nullptr);
  doc["float_map_format"] = "float32 little-endian, row-major, top row first; V = |a - 1 g| in g; 0 where no taxel";
  doc["mm_per_pixel"] = r.mmPerPixel;
  doc["physical_size_m"] = r.physicalSize_m;
  doc["normalisation"] = normalisationJson(range);
  if (r.authorsMap) {
    // run.py's map: divided by its largest taxel value, warped with the uncovered zeros blended in.
    doc["normalisation"] = {{"min_g", 0.0}, {"max_g", r.stats.max},
                            {"formula", "png = V / max_g (8 bits), drawn, warped and cropped as the authors' run.py does "
                                        "(--compat reference)"}};
  }
  doc["coverage"] = r.map.coverage.pixels.empty() ? 0.0 : double(range.covered) / double(r.map.coverage.pixels.size());
  doc["statistics"] = statsJson(r.stats, taxels);
  doc["statistics_noise_corrected"] = correctedJson(r.noise, r.statsCorrected, taxels);
  doc["noise"] = {{"sigma_g", r.noise.known ? nlohmann::json(r.noise.sigma_g) : nlohmann::json(nullptr)},
                  {"rest_samples", r.noise.samples},
                  {"method", "standard deviation of the accelerometer readings while the robot stood still before and "
                             "after each pass"}};
  const auto axisName = [](int axis) { return axis == 0 ? "x" : "y"; };
  const glm::dvec2 along = scanDirectionUv(r, r.axis);
  doc["scan_axis"] = axisName(r.axis);
  doc["scan_direction_uv"] = {along.x, along.y};
  if (r.across) {
    // The across map has its own range (its values lie below the main map's on a grating: with
    // the main map's range its PNG would be all zeros); the loader brings both back to g.
    const CoveredRange acrossRange = coveredRange(r.across->map);
    saveMapPng(dir / (name + "_acc_across.png"), r.across->map, acrossRange.lo, acrossRange.hi);
    if (writeFloatMap) saveFloatMap(dir / (name + "_map_across.f32"), r.across->map);
    const int axis = 1 - r.axis;
    const glm::dvec2 d = scanDirectionUv(r, axis);
    doc["across"] = {{"map_png", name + "_acc_across.png"},
                     {"float_map", writeFloatMap ? nlohmann::json(name + "_map_across.f32") : nlohmann::json(nullptr)},
                     {"scan_axis", axisName(axis)},
                     {"scan_direction_uv", {d.x, d.y}},
                     {"normalisation", normalisationJson(acrossRange)},
                     {"lines", r.across->lines.size()},
                     {"statistics", statsJson(r.across->stats, taxelCount(r.across->lines))},
                     {"statistics_noise_corrected",
                      correctedJson(r.noise, r.across->statsCorrected, taxelCount(r.across->lines))}};
  }
  doc["calibration"] = {{"file", name + "_calibration.json"},
                        {"reprojection_rms_px", r.calibration.rmsError_px},
                        {"reprojection_max_px", r.calibration.maxError_px}};
  doc["lines"] = r.lines.size();
  doc["taxel_size_m"] = r.config.taxelSize_m;
  writeFileAtomically(dir / (name + "_map.json"), doc.dump(2) + "\n");
  staged.commit();
}

}  // namespace vt::acq
