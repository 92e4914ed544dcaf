// Writes one object in the published Pixel2Taxel layout plus our float map, header,
// preview and calibration report (docs/scan-format.md, "Output").
#include <bit>

#include <nlohmann/json.hpp>

#include "vt/acquisition/pipeline.hpp"
#include "vt/core/error.hpp"
#include "vt/core/output_file.hpp"

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

}  // namespace

void writeDataset(const AcquireResult& r, const std::filesystem::path& outDir, bool writeFloatMap, bool replace) {
  static_assert(std::endian::native == std::endian::little, "the .f32 format is little-endian");
  const std::string& name = r.config.name;
  // The object is built whole in a hidden folder and moved into place: a failure (a full disk)
  // leaves the previous object as it was, and a replaced object keeps no stale files.
  StagedFolder staged(outDir / name, replace);
  const auto& dir = staged.dir();

  savePng(dir / (name + ".png"), r.photo);
  const ImageF normalised = normaliseMap(r.map);
  Image16 acc(normalised.width, normalised.height, 1);
  for (std::size_t i = 0; i < acc.pixels.size(); ++i) acc.pixels[i] = std::uint16_t(normalised.pixels[i] * 65535.0f + 0.5f);
  savePng16(dir / (name + "_acc.png"), acc);
  savePng(dir / (name + "_preview.png"), makePreview(r.photo, r.map, normalised));
  writeFileAtomically(dir / (name + "_calibration.json"), calibrationReportJson(r.calibration, r.calibrationPoints));

  float lo = 0, hi = 0;
  std::size_t covered = 0;
  for (std::size_t i = 0; i < r.map.coverage.pixels.size(); ++i) {
    if (!r.map.coverage.pixels[i]) continue;
    const float v = r.map.value_g.pixels[i];
    lo = covered ? std::min(lo, v) : v;
    hi = covered ? std::max(hi, v) : v;
    ++covered;
  }
  if (writeFloatMap) {
    writeFileAtomically(dir / (name + "_map.f32"),
                        std::string_view(reinterpret_cast<const char*>(r.map.value_g.pixels.data()),
                                         r.map.value_g.pixels.size() * sizeof(float)));
  }
  std::size_t taxels = 0;
  for (const LineResult& line : r.lines) taxels += line.taxels.size();
  nlohmann::json doc;
  doc["name"] = name;
  doc["width"] = r.photo.width;
  doc["height"] = r.photo.height;
  doc["photo"] = name + ".png";
  doc["map_png"] = name + "_acc.png";
  doc["map_png_bits"] = 16;
  doc["float_map"] = writeFloatMap ? nlohmann::json(name + "_map.f32") : nlohmann::json(nullptr);
  doc["float_map_format"] = "float32 little-endian, row-major, top row first; V = |a - 1 g| in g; 0 where no taxel";
  doc["mm_per_pixel"] = r.mmPerPixel;
  doc["physical_size_m"] = r.physicalSize_m;
  doc["normalisation"] = {{"min_g", lo}, {"max_g", hi}, {"formula", "png = (V - min_g) / (max_g - min_g)"}};
  doc["coverage"] = r.map.coverage.pixels.empty() ? 0.0 : double(covered) / double(r.map.coverage.pixels.size());
  doc["statistics"] = {{"v_scale_g", r.stats.scale}, {"v_mean_g", r.stats.mean}, {"v_std_g", r.stats.std},
                       {"v_min_g", r.stats.min},     {"v_max_g", r.stats.max},   {"taxels", taxels},
                       {"source", "taxel values before normalisation"}};
  doc["calibration"] = {{"file", name + "_calibration.json"},
                        {"reprojection_rms_px", r.calibration.rmsError_px},
                        {"reprojection_max_px", r.calibration.maxError_px}};
  doc["lines"] = r.lines.size();
  doc["taxel_size_m"] = r.config.taxelSize_m;
  writeFileAtomically(dir / (name + "_map.json"), doc.dump(2) + "\n");
  staged.commit();
}

}  // namespace vt::acq
