// Measured waveforms per taxel: written by the acquisition, loaded and played by the
// application's taxel model, with the spectrum of what was scanned.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "scan_fixture.hpp"
#include "vt/acquisition/pipeline.hpp"
#include "vt/acquisition/waveforms.hpp"
#include "vt/haptics/signal_analysis.hpp"
#include "vt/haptics/tactile_model.hpp"
#include "vt/haptics/vibration_map.hpp"

using namespace vt::acq;

TEST_CASE("measured taxel waveforms play back with the scanned spectrum") {
  SyntheticOptions o = test::smallOptions(SyntheticKind::NotebookCover);
  const auto scan = test::writeScan("waveforms_grating", o);
  const Scan loaded = loadScan(scan.dir);
  // Without the placed samples there is nothing to cut from, and measureWaveforms says so.
  CHECK_THROWS_WITH(measureWaveforms(acquire(loaded, {.jobs = 2})), Catch::Matchers::Contains("keepSamples"));
  const AcquireResult r = acquire(loaded, {.jobs = 2, .keepSamples = true});
  const WaveformGrid grid = measureWaveforms(r);
  // One taxel crossing (1 mm at 20 mm/s) at 8 kHz; 1 mm cells over the 20 x 12 mm image.
  CHECK(grid.samplesPerCell == 400);
  CHECK(grid.width == 20);
  CHECK(grid.height == 12);
  const auto measured = std::count(grid.measured.begin(), grid.measured.end(), 1);
  CHECK(measured > grid.width * grid.height * 8 / 10);

  const auto dir = vt::test::outputDir("waveforms_grating_out") / "waveforms";
  writeWaveforms(grid, dir);
  const auto info = nlohmann::json::parse(std::ifstream(dir / "waveforms.json"));
  CHECK(info["samples_per_taxel"] == 400);
  const auto map = vt::haptics::loadTaxelWaveforms(dir, {info["samples_per_taxel"].get<int>()});
  REQUIRE(map.width() == grid.width);
  REQUIRE(map.height() == grid.height);

  // What was scanned: the accelerometer along the middle line (pass 0, constant velocity).
  const LineResult& line = r.lines[3];
  const double tMid = 0.5 * (line.firstPass.front().t_s + line.firstPass.back().t_s);
  std::vector<float> scanned;
  for (const PlacedSample& s : line.firstPass)
    if (std::abs(s.t_s - tMid) < 0.4) scanned.push_back(s.a_g);
  const double fScanned = vt::haptics::dominantFrequency_hz(scanned, o.accelRate_hz, 10.0, 240.0);

  // What the taxel model plays: a finger sliding along the middle row at 8 kHz for 0.5 s.
  vt::haptics::TactileModel renderer({.model = vt::haptics::TactileModelKind::TaxelWaveform, .sampleRate_hz = 8000.0f});
  std::vector<float> played;
  std::array<float, 8> block{};
  glm::vec2 uv{0.2f, 0.5f};
  for (int tick = 0; tick < 500; ++tick) {
    vt::haptics::ContactInput in;
    in.inContact = true;
    in.map = &map;
    in.uvStart = uv;
    uv.x += 0.6f / 500.0f;
    in.uvEnd = uv;
    renderer.render(in, block);
    for (float s : block) played.push_back(s);
  }
  const double fPlayed = vt::haptics::dominantFrequency_hz(played, 8000.0, 10.0, 240.0);
  INFO("scanned " << fScanned << " Hz, played " << fPlayed << " Hz");
  // The fine texture: 0.5 mm period crossed at 20 mm/s = 40 Hz.
  CHECK(fScanned == Approx(40.0).epsilon(0.05));
  CHECK(fPlayed == Approx(fScanned).epsilon(0.05));
}
