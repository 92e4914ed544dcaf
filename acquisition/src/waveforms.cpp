#include "vt/acquisition/waveforms.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>

#include <nlohmann/json.hpp>

#include "vt/core/error.hpp"
#include "vt/core/output_file.hpp"
#include "parallel.hpp"

namespace vt::acq {
namespace {

// The lines that kept their first pass, by across position, to find the nearest one quickly.
std::vector<const LineResult*> linesByAcross(const std::vector<LineResult>& lines) {
  std::vector<const LineResult*> sorted;
  for (const LineResult& line : lines)
    if (!line.passes.empty() && !line.firstPass.empty()) sorted.push_back(&line);
  std::stable_sort(sorted.begin(), sorted.end(), [](const LineResult* a, const LineResult* b) { return a->x_m < b->x_m; });
  return sorted;
}

// The line whose across position is nearest to `across_m` (the earlier one on a tie).
const LineResult* nearestLine(const std::vector<const LineResult*>& sorted, double across_m) {
  if (sorted.empty()) return nullptr;
  const auto it = std::lower_bound(sorted.begin(), sorted.end(), across_m, [](const LineResult* l, double x) { return l->x_m < x; });
  if (it == sorted.end()) return sorted.back();
  if (it == sorted.begin()) return *it;
  const LineResult* before = *(it - 1);
  return std::abs(before->x_m - across_m) <= std::abs((*it)->x_m - across_m) ? before : *it;
}

// Pass 0's signal around the time it crossed `along_m`, resampled to `out` (linear, held at
// the ends of what was measured). The pass's samples are in time order: one binary search.
void cutSegment(const LineResult& line, double along_m, double rate_hz, std::span<float> out) {
  const PassFit& fit = line.passes[0];
  const std::vector<PlacedSample>& pass = line.firstPass;
  const double duration = double(out.size()) / rate_hz;
  const double tCentre = (along_m - fit.intercept_m) / fit.slope_m_per_s;
  const double t0 = std::clamp(tCentre - duration / 2, pass.front().t_s, std::max(pass.front().t_s, pass.back().t_s - duration));
  const auto byTime = [](const PlacedSample& s, double t) { return s.t_s < t; };
  std::size_t j = std::size_t(std::lower_bound(pass.begin(), pass.end(), t0, byTime) - pass.begin());
  j = j > 0 ? j - 1 : 0;
  // Linear between the measured samples: each sample interval's slope once, not per output sample.
  std::size_t slopeAt = pass.size();
  double slope = 0.0;
  for (std::size_t k = 0; k < out.size(); ++k) {
    const double t = t0 + double(k) / rate_hz;
    while (j + 1 < pass.size() && pass[j + 1].t_s <= t) ++j;
    float a = pass[j].a_g;
    if (j + 1 < pass.size() && t > pass[j].t_s) {
      if (slopeAt != j) slopeAt = j, slope = (pass[j + 1].a_g - pass[j].a_g) / (pass[j + 1].t_s - pass[j].t_s);
      a = float(pass[j].a_g + slope * (t - pass[j].t_s));  // t < t[j + 1]: within the interval
    }
    out[k] = 1.0f + a;  // the format stores the accelerometer reading (rest = 1 g)
  }
}

}  // namespace

WaveformGrid measureWaveforms(const AcquireResult& r, const WaveformOptions& options) {
  const std::string where = str("waveforms of '", r.config.name, "'");
  if (!(options.rate_hz >= 100 && options.rate_hz <= 96000)) fail(where, ": rate ", options.rate_hz, " Hz out of range 100..96000");
  if (!(options.duration_s >= 0 && options.duration_s <= 1)) fail(where, ": duration ", options.duration_s, " s out of range 0..1");
  if (r.lines.empty() || r.photo.width < 1 || r.mmPerPixel[0] <= 0 || r.mmPerPixel[1] <= 0) fail(where, ": no map to cut from");
  if (std::all_of(r.lines.begin(), r.lines.end(), [](const LineResult& line) { return line.firstPass.empty(); })) {
    fail(where, ": the lines kept no samples (acquire with AcquireOptions::keepSamples)");
  }
  double duration = options.duration_s;
  if (duration == 0) {
    std::vector<double> speeds;
    for (const LineResult& line : r.lines)
      for (const PassFit& p : line.passes) speeds.push_back(std::abs(p.slope_m_per_s));
    std::nth_element(speeds.begin(), speeds.begin() + long(speeds.size() / 2), speeds.end());
    duration = r.config.taxelSize_m / speeds[speeds.size() / 2];
  }
  const double cell_mm = (options.cell_m > 0 ? options.cell_m : r.config.taxelSize_m) * 1e3;
  WaveformGrid grid;
  grid.rate_hz = options.rate_hz;
  grid.samplesPerCell = std::max(1, int(std::lround(duration * options.rate_hz)));
  grid.width = std::max(1, int(std::lround(r.photo.width * r.mmPerPixel[0] / cell_mm)));
  grid.height = std::max(1, int(std::lround(r.photo.height * r.mmPerPixel[1] / cell_mm)));
  const std::size_t cells = std::size_t(grid.width) * std::size_t(grid.height);
  if (cells * std::size_t(grid.samplesPerCell) > (std::size_t(1) << 28)) {
    fail(where, ": ", grid.width, "x", grid.height, " cells of ", grid.samplesPerCell, " samples is too large (use a larger cell)");
  }
  grid.samples.assign(cells * std::size_t(grid.samplesPerCell), 1.0f);
  grid.measured.assign(cells, 0);
  const auto outputToPhoto = inverse3x3(r.photoToOutput);
  const std::vector<const LineResult*> sorted = linesByAcross(r.lines);
  // Rows are independent: cut on the threads the acquisition used.
  detail::parallelFor(
      std::size_t(grid.height), r.jobs,
      [&](std::size_t rowIndex) {
        const int row = int(rowIndex);
        for (int col = 0; col < grid.width; ++col) {
          const glm::dvec2 px{(col + 0.5) * r.photo.width / grid.width - 0.5, (row + 0.5) * r.photo.height / grid.height - 0.5};
          const int ix = std::clamp(int(std::lround(px.x)), 0, r.photo.width - 1);
          const int iy = std::clamp(int(std::lround(px.y)), 0, r.photo.height - 1);
          if (!r.map.coverage.at(ix, iy)) continue;
          const glm::dvec2 world = r.calibration.camera.planePoint(applyHomography(outputToPhoto, px));
          const int along = r.axis, across = 1 - along;
          const LineResult* line = nearestLine(sorted, world[across]);
          if (!line) continue;
          const std::size_t cell = std::size_t(row) * std::size_t(grid.width) + std::size_t(col);
          cutSegment(*line, world[along], grid.rate_hz,
                     {grid.samples.data() + cell * std::size_t(grid.samplesPerCell), std::size_t(grid.samplesPerCell)});
          grid.measured[cell] = 1;
        }
      },
      [](std::size_t) {});
  return grid;
}

void writeWaveforms(const WaveformGrid& grid, const std::filesystem::path& dir) {
  static_assert(std::endian::native == std::endian::little, "header.bin and data.bin are little-endian");
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) fail("cannot create '", dir.string(), "': ", ec.message());
  // Empty cells own no samples (their start equals the next one's): the player plays silence.
  // Each file through an OutputFile: every write and the close checked, a full disk named; the
  // samples go out cell by cell, without a second copy of them.
  std::vector<std::int32_t> header{grid.height, grid.width};
  const auto n = std::size_t(grid.samplesPerCell);
  std::int32_t start = 0;
  for (std::size_t cell = 0; cell < grid.measured.size(); ++cell) {
    header.push_back(start);
    if (grid.measured[cell]) start += std::int32_t(n);
  }
  writeFileAtomically(dir / "header.bin", std::string_view(reinterpret_cast<const char*>(header.data()),
                                                           header.size() * sizeof(std::int32_t)));
  OutputFile data(dir / "data.bin");
  for (std::size_t cell = 0; cell < grid.measured.size(); ++cell) {
    if (grid.measured[cell]) data.write(grid.samples.data() + cell * n, n * sizeof(float));
  }
  data.commit();
  const auto write = [](const std::filesystem::path& path, const void* bytes, std::size_t size) {
    writeFileAtomically(path, std::string_view(static_cast<const char*>(bytes), size));
  };
  nlohmann::json doc;
  doc["format"] = "header.bin: int32 height, width, one start index per cell (row-major, top row first) into data.bin; "
                  "data.bin: float32 accelerometer readings in g (rest = 1 g)";
  doc["width"] = grid.width;
  doc["height"] = grid.height;
  doc["sample_rate_hz"] = grid.rate_hz;
  doc["samples_per_taxel"] = grid.samplesPerCell;
  doc["duration_s"] = grid.samplesPerCell / grid.rate_hz;
  const std::string text = doc.dump(2) + "\n";
  write(dir / "waveforms.json", text.data(), text.size());
}

}  // namespace vt::acq
