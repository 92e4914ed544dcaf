#pragma once
// Measured waveforms per taxel: for a grid of cells over the final image, the acceleration the
// stylus felt there (one pass's segment, resampled to a fixed rate), written in the format the
// application plays with `--model taxel` (waveforms/header.bin + data.bin). Any thread.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "vt/acquisition/pipeline.hpp"

namespace vt::acq {

/// How the waveforms are cut and sampled.
struct WaveformOptions {
  double rate_hz = 8000.0;  // output rate (the application's default output rate: played 1:1)
  double duration_s = 0.0;  // per cell; 0 = the time the stylus takes to cross one taxel
  double cell_m = 0.0;      // grid cell size on the object; 0 = the taxel size
};

/// One waveform per grid cell (row-major, row 0 = top of the final image), in g with the
/// accelerometer's 1 g rest included (the format's convention); cells off the map are empty.
struct WaveformGrid {
  int width = 0, height = 0;
  int samplesPerCell = 0;
  double rate_hz = 0.0;
  std::vector<float> samples;  // (row * width + col) * samplesPerCell + i
  std::vector<std::uint8_t> measured;  // per cell: 1 on the map (0: empty in header.bin); bytes, so rows fill in parallel
};

/// Cuts the waveforms from the main map's lines (pass 0 of the nearest line at each cell).
WaveformGrid measureWaveforms(const AcquireResult& result, const WaveformOptions& options = {});

/// Writes DIR/header.bin, DIR/data.bin and DIR/waveforms.json (rate, samples per cell); writeDataset
/// calls it inside the dataset object's staged folder.
void writeWaveforms(const WaveformGrid& grid, const std::filesystem::path& dir);

}  // namespace vt::acq
