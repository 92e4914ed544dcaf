// HJIF / AHAP / Meta .haptic: round trips within stated tolerances, and every written file
// checked against the structure its specification defines (none publishes a JSON schema we can
// fetch: the HJIF schemas live in MPEG's own repository; Apple and Meta publish prose rules).
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <numbers>

#include <nlohmann/json.hpp>

#include "test_support.hpp"
#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/haptics/devices/recorder.hpp"
#include "vt/haptics/files/clip_player.hpp"
#include "vt/haptics/files/haptic_formats.hpp"

using Catch::Matchers::Contains;
using nlohmann::json;
namespace files = vt::haptics::files;
using vt::haptics::ActuatorFrame;
using vt::haptics::ActuatorId;

namespace {

constexpr int kRate_hz = 8000, kBlock = 8;

// 0.6 s at 1 kHz ticks: the index finger ramps up a 250 Hz sine and stops; the thumb is silent
// until 0.2 s, then holds 0.3 at 120 Hz.
ActuatorFrame syntheticFrame(int tick) {
  ActuatorFrame f;
  f.sequence = std::uint64_t(tick);
  f.t_ns = std::int64_t(tick) * 1'000'000;
  f.actuatorCount = 2, f.blockLength = kBlock, f.sampleRate_hz = kRate_hz;
  const double t = tick * 1e-3;
  const float index = t < 0.4 ? float(t / 0.4) : 0.0f;
  const float thumb = t >= 0.2 ? 0.3f : 0.0f;
  f.intensity = {thumb, index};
  f.frequency_hz = {thumb > 0 ? 120.0f : 0.0f, 250.0f};
  for (int k = 0; k < kBlock; ++k) {
    const double ts = t + double(k) / kRate_hz;
    f.block[0][std::size_t(k)] = thumb * float(std::sin(2 * std::numbers::pi * 120 * ts));
    f.block[1][std::size_t(k)] = index * float(std::sin(2 * std::numbers::pi * 250 * ts));
  }
  return f;
}

files::HapticClip recordSynthetic(const std::filesystem::path& dir) {
  {
    vt::haptics::ActuatorRecorder recorder(dir / "rec.csv", dir / "rec.wav", 2);
    for (int tick = 0; tick < 600; ++tick) recorder.record(syntheticFrame(tick));
    recorder.finish();
  }
  return files::loadRecording(dir / "rec.csv", dir / "rec.wav");
}

// The envelope round-trip tolerance: amplitude within 0.01, frequency within 1 Hz.
void checkEnvelopeKept(const files::ClipChannel& original, const files::ClipChannel& back) {
  for (double t = 0.0; t < 0.6; t += 0.0137) {
    const auto a = files::envelopeAt(original.envelope, t);
    const auto b = files::envelopeAt(back.envelope, t);
    CHECK(b.amplitude == Approx(a.amplitude).margin(0.01));
    CHECK(b.frequency_hz == Approx(a.frequency_hz).margin(1.0));
  }
}

json readJson(const std::filesystem::path& path) {
  std::ifstream in(path);
  return json::parse(in);
}

// ISO/IEC 23090-31 HJIF: the members the reference software requires at each level.
void checkHjifStructure(const json& doc) {
  for (const char* key : {"version", "profile", "date", "description"}) REQUIRE(doc.at(key).is_string());
  CHECK((doc["profile"] == "Main" || doc["profile"] == "Simple Parametric"));
  CHECK((doc.at("level") == 1 || doc.at("level") == 2));
  REQUIRE(doc.at("timescale").is_number_unsigned());
  CHECK(doc["timescale"].get<unsigned>() <= 48000);
  REQUIRE(doc.at("syncs").is_array());
  for (const json& avatar : doc.at("avatars")) {
    CHECK(avatar.at("id").get<int>() != 0);  // 0 is reserved
    CHECK(avatar.at("lod").is_number_integer());
    CHECK(avatar.at("type") == "Vibration");
  }
  for (const json& perception : doc.at("perceptions")) {
    for (const char* key : {"id", "avatar_id"}) CHECK(perception.at(key).is_number_integer());
    CHECK(perception.at("perception_modality") == "Vibrotactile");
    CHECK(perception.at("effect_library").is_array());
    CHECK(perception.at("channels").size() <= 128);
    for (const json& channel : perception["channels"]) {
      CHECK(channel.at("id").is_number_integer());
      CHECK(channel.at("description").is_string());
      CHECK(channel.at("gain").is_number());
      CHECK(channel.at("mixing_coefficient").is_number());
      CHECK(channel.at("body_part_mask").is_number_unsigned());
      CHECK(channel.at("body_part_target").at(1) == "Hand");
      for (const json& band : channel.at("bands")) {
        const std::string type = band.at("band_type");
        CHECK((type == "Curve" || type == "VectorialWave"));
        CHECK(band.at("lower_frequency_limit").is_number_integer());
        CHECK(band.at("upper_frequency_limit").get<int>() >= band["lower_frequency_limit"].get<int>());
        CHECK(band.contains("curve_type") == (type == "Curve"));
        for (const json& effect : band.at("effects")) {
          CHECK(effect.at("effect_type") == "Basis");
          CHECK(effect.at("position").is_number_integer());
          long last = -1;
          for (const json& k : effect.at("keyframes")) {
            REQUIRE(k.at("relative_position").is_number_integer());
            CHECK(k["relative_position"].get<long>() > last);
            last = k["relative_position"].get<long>();
            CHECK(std::fabs(k.at("amplitude_modulation").get<double>()) <= 1.0);
          }
        }
      }
    }
  }
}

// Apple's AHAP: Version, a Pattern of single-key entries, continuous events of at most 30 s,
// parameter curves of at most 16 control points, values in their documented ranges.
void checkAhapStructure(const json& doc) {
  REQUIRE(doc.at("Version").is_number());
  for (const json& entry : doc.at("Pattern")) {
    REQUIRE(entry.size() == 1);
    if (entry.contains("Event")) {
      const json& e = entry["Event"];
      CHECK(e.at("EventType") == "HapticContinuous");
      CHECK(e.at("Time").get<double>() >= 0.0);
      CHECK(e.at("EventDuration").get<double>() <= 30.0);
      for (const json& p : e.at("EventParameters")) {
        CHECK((p.at("ParameterID") == "HapticIntensity" || p.at("ParameterID") == "HapticSharpness"));
        CHECK(p.at("ParameterValue").get<double>() >= 0.0);
        CHECK(p.at("ParameterValue").get<double>() <= 1.0);
      }
    } else {
      const json& c = entry.at("ParameterCurve");
      CHECK((c.at("ParameterID") == "HapticIntensityControl" || c.at("ParameterID") == "HapticSharpnessControl"));
      CHECK(c.at("ParameterCurveControlPoints").size() <= 16);
      CHECK(c.at("ParameterCurveControlPoints").at(0).at("Time") == 0.0);
    }
  }
}

// Meta .haptic 1.0's validation rules (haptic-file-spec.md).
void checkMetaHapticStructure(const json& doc) {
  CHECK(doc.at("version") == json({{"major", 1}, {"minor", 0}, {"patch", 0}}));
  REQUIRE(doc.at("metadata").is_object());
  const json& envelopes = doc.at("signals").at("continuous").at("envelopes");
  const json& amplitude = envelopes.at("amplitude");
  REQUIRE(amplitude.size() >= 2);
  double last = 0.0;
  for (const json& p : amplitude) {
    CHECK(p.at("time").get<double>() >= last);
    last = p["time"].get<double>();
    CHECK(p.at("amplitude").get<double>() >= 0.0);
    CHECK(p.at("amplitude").get<double>() <= 1.0);
  }
  CHECK(last > 0.0);
  for (const json& p : envelopes.at("frequency")) {
    CHECK(p.at("time").get<double>() <= last);  // no overshoot past the amplitude envelope
    CHECK(p.at("frequency").get<double>() >= 0.0);
    CHECK(p.at("frequency").get<double>() <= 1.0);
  }
}

}  // namespace

TEST_CASE("A recording's CSV and WAV become a clip of its active actuators", "[files]") {
  const auto clip = recordSynthetic(vt::test::outputDir("files_recording"));
  REQUIRE(clip.channels.size() == 2);
  CHECK(clip.channels[0].actuator == ActuatorId::Thumb);
  CHECK(clip.channels[1].actuator == ActuatorId::Index);
  CHECK(clip.sampleRate_hz == kRate_hz);
  CHECK(clip.channels[1].pcm.size() == 600u * kBlock);
  CHECK(clip.duration_s == Approx(0.6));
  CHECK(files::envelopeAt(clip.channels[1].envelope, 0.2).amplitude == Approx(0.5f).margin(0.01));
}

TEST_CASE("An actuator CSV written before the finger names were unified (\"pinky\") still reads", "[files]") {
  const auto dir = vt::test::outputDir("files_legacy_names");
  std::ofstream(dir / "old.csv") << "t_ns,sequence,pinky,palm-pinky-up,pinky_hz,palm-pinky-up_hz\n"
                                    "0,0,0.5,0,200,0\n"
                                    "1000000,1,0.25,0.5,200,150\n";
  const auto clip = files::loadRecording(dir / "old.csv", "");
  REQUIRE(clip.channels.size() == 2);
  CHECK(clip.channels[0].actuator == ActuatorId::Little);
  CHECK(clip.channels[1].actuator == ActuatorId::PalmLittleUp);
  CHECK(files::actuatorFromFileName("clip-pinky.ahap", ActuatorId::Thumb) == ActuatorId::Little);
  CHECK(files::actuatorFromFileName("clip-palm-little-down.ahap", ActuatorId::Thumb) == ActuatorId::PalmLittleDown);
}

TEST_CASE("HJIF keeps the waveform sample for sample and follows the standard's structure", "[files][hjif]") {
  const auto dir = vt::test::outputDir("files_hjif");
  const auto clip = recordSynthetic(dir);
  REQUIRE(files::saveHapticFile(clip, dir / "rec.hjif", false).size() == 1);
  checkHjifStructure(readJson(dir / "rec.hjif"));
  const auto back = files::loadHapticFile(dir / "rec.hjif");
  REQUIRE(back.channels.size() == 2);
  CHECK(back.sampleRate_hz == kRate_hz);
  for (std::size_t c = 0; c < 2; ++c) {
    CHECK(back.channels[c].actuator == clip.channels[c].actuator);
    REQUIRE(back.channels[c].pcm.size() == clip.channels[c].pcm.size());
    float worst = 0.0f;
    for (std::size_t i = 0; i < clip.channels[c].pcm.size(); ++i) {
      worst = std::max(worst, std::fabs(back.channels[c].pcm[i] - clip.channels[c].pcm[i]));
    }
    CHECK(worst < 1e-6f);  // tolerance: exact up to float printing
  }
  // Envelope only (CSV without WAV): a VectorialWave band, amplitude within 0.01, frequency within 1 Hz.
  const auto envelopeClip = files::loadRecording(dir / "rec.csv", "");
  files::saveHapticFile(envelopeClip, dir / "envelope.hjif", false);
  checkHjifStructure(readJson(dir / "envelope.hjif"));
  const auto envelopeBack = files::loadHapticFile(dir / "envelope.hjif");
  checkEnvelopeKept(envelopeClip.channels[1], envelopeBack.channels[1]);
}

TEST_CASE("AHAP and .haptic carry each actuator's envelope in one file per actuator", "[files][ahap][haptic]") {
  const auto dir = vt::test::outputDir("files_ahap_haptic");
  recordSynthetic(dir);
  const auto clip = files::loadRecording(dir / "rec.csv", "");
  for (const char* ext : {".ahap", ".haptic"}) {
    const auto written = files::saveHapticFile(clip, dir / (std::string("rec") + ext), false);
    REQUIRE(written.size() == 2);
    // Any file of the set existing refuses the whole set, unless replaced on purpose.
    std::filesystem::remove(written[0]);
    REQUIRE_THROWS_WITH(files::saveHapticFile(clip, dir / (std::string("rec") + ext), false),
                        Contains(written[1].string() + "' already exists (use --force"));
    CHECK_FALSE(std::filesystem::exists(written[0]));
    CHECK(files::saveHapticFile(clip, dir / (std::string("rec") + ext), true) == written);
    CHECK(written[1].filename() == std::string("rec-index") + ext);
    const json doc = readJson(written[1]);
    std::string(ext) == ".ahap" ? checkAhapStructure(doc) : checkMetaHapticStructure(doc);
    const auto back = files::loadHapticFile(written[1], ActuatorId::Little);
    REQUIRE(back.channels.size() == 1);
    CHECK(back.channels[0].actuator == ActuatorId::Index);  // from the file name, not the fallback
    INFO(ext);
    checkEnvelopeKept(clip.channels[1], back.channels[0]);
  }
}

TEST_CASE("AHAP splits long clips into 30 s events and 16-point curves", "[files][ahap]") {
  files::HapticClip clip;
  clip.duration_s = 65.0;
  clip.channels.emplace_back();
  for (int i = 0; i <= 650; ++i) clip.channels[0].envelope.push_back({i * 0.1, float(i % 2), 200.0f});
  const json doc = json::parse(files::writeAhap(clip, 0));
  checkAhapStructure(doc);
  int events = 0;
  for (const json& e : doc["Pattern"]) events += e.contains("Event");
  CHECK(events == 3);
  const auto back = files::readAhap(doc.dump(), "long.ahap", ActuatorId::Index);
  CHECK(back.duration_s == Approx(65.0));
  CHECK(files::envelopeAt(back.channels[0].envelope, 43.1).amplitude == Approx(1.0f).margin(0.01));
  CHECK(files::envelopeAt(back.channels[0].envelope, 43.2).amplitude == Approx(0.0f).margin(0.01));
}

TEST_CASE("Haptic file errors name the file and the field", "[files]") {
  REQUIRE_THROWS_WITH(files::readMetaHaptic(R"({"version":{"major":1,"minor":0,"patch":0},"metadata":{},
      "signals":{"continuous":{"envelopes":{"amplitude":[{"time":0,"amplitude":0.2}],"frequency":[]}}}})", "one.haptic",
                                            ActuatorId::Index),
                      Contains("one.haptic") && Contains("at least two breakpoints"));
  REQUIRE_THROWS_WITH(files::readMetaHaptic(R"({"version":{"major":1,"minor":0,"patch":0},"metadata":{},
      "signals":{"continuous":{"envelopes":{"amplitude":[{"time":0,"amplitude":0.5,"emphasis":{"amplitude":0.2,"frequency":1}},
      {"time":1,"amplitude":0}]}}}})", "emph.haptic", ActuatorId::Index),
                      Contains("amplitude[0].emphasis.amplitude"));
  REQUIRE_THROWS_WITH(files::readAhap(R"({"Version":1,"Pattern":[{"Event":{"Time":0,"EventType":"Boom","EventParameters":[]}}]})",
                                      "x.ahap", ActuatorId::Index),
                      Contains("x.ahap: Pattern[0].Event.EventType 'Boom'"));
  REQUIRE_THROWS_WITH(files::readHjif(R"({"version":"2023","profile":"Main","level":1,"date":"2025","description":"",
      "timescale":1000,"avatars":[],"syncs":[],"perceptions":[{"id":0,"avatar_id":0,"description":"","perception_modality":
      "Vibrotactile","effect_library":[],"channels":[{"id":0,"description":"index","gain":1,"mixing_coefficient":1,
      "body_part_mask":0,"bands":[{"band_type":"WaveletWave","lower_frequency_limit":0,"upper_frequency_limit":1000,
      "effects":[]}]}]}]})", "w.hjif"),
                      Contains("w.hjif: perceptions[0].channels[0].bands[0]") && Contains("WaveletWave"));
  REQUIRE_THROWS_WITH(files::readHjif("[1,2]", "arr.hjif"), Contains("arr.hjif") && Contains("top level"));
  REQUIRE_THROWS_WITH(files::loadHapticFile("clip.mp3"), Contains("clip.mp3") && Contains(".hjif, .ahap, .haptic or .wav"));
  // Files are read through vt::readInputFile: a folder, a symlink loop or an oversized file is one line naming it.
  const auto dir = vt::test::outputDir("files_errors");
  std::filesystem::create_directories(dir / "dir.hjif");
  std::filesystem::create_directories(dir / "dir.csv");
  std::filesystem::create_directories(dir / "dir.wav");
  std::filesystem::create_symlink("loop.ahap", dir / "loop.ahap");
  REQUIRE_THROWS_WITH(files::loadHapticFile(dir / "dir.hjif"), Contains("dir.hjif': is a folder, expected a file"));
  REQUIRE_THROWS_WITH(files::loadHapticFile(dir / "loop.ahap"), Contains("loop.ahap': cannot read: too many levels"));
  REQUIRE_THROWS_WITH(files::loadRecording(dir / "dir.csv", ""), Contains("dir.csv': is a folder, expected a file"));
  REQUIRE_THROWS_WITH(files::loadRecording("", dir / "dir.wav"), Contains("dir.wav': is a folder, expected a file"));
  std::ofstream(dir / "big.haptic").close();
  std::filesystem::resize_file(dir / "big.haptic", vt::budget::kHapticFileBytes + 1);  // sparse
  REQUIRE_THROWS_WITH(files::loadHapticFile(dir / "big.haptic"), Contains("big.haptic': 134217729 bytes is over the limit"));
}

TEST_CASE("A small HJIF cannot ask for more waveform than the clip budget", "[files][hjif]") {
  // A channel of `samples` samples at 48 kHz; `perceptions` copies of a perception with `channels` channels.
  auto hjif = [](int perceptions, int channels, long samples) {
    json channel = {{"id", 0}, {"description", "index"}, {"gain", 1}, {"mixing_coefficient", 1}, {"body_part_mask", 0},
                    {"frequency_sampling", 48000}, {"sample_count", samples},
                    {"bands", {{{"band_type", "Curve"}, {"lower_frequency_limit", 0}, {"upper_frequency_limit", 1000},
                                {"effects", {{{"effect_type", "Basis"}, {"position", 0},
                                              {"keyframes", {{{"relative_position", 0}, {"amplitude_modulation", 0.5}},
                                                             {{"relative_position", 10}, {"amplitude_modulation", 0.1}}}}}}}}}}};
    json perception = {{"id", 0}, {"avatar_id", 0}, {"description", ""}, {"perception_modality", "Vibrotactile"},
                       {"effect_library", json::array()}, {"channels", json::array()}};
    json doc = {{"version", "2023"}, {"profile", "Main"}, {"level", 1}, {"date", "2025"}, {"description", ""},
                {"timescale", 48000}, {"avatars", json::array()}, {"syncs", json::array()}, {"perceptions", json::array()}};
    for (int p = 0; p < perceptions; ++p) {
      doc["perceptions"].push_back(perception);
      for (int c = 0; c < channels; ++c) {  // each channel on its own actuator
        channel["description"] = vt::haptics::actuatorName(ActuatorId((p * channels + c) % vt::haptics::kMaxActuators));
        doc["perceptions"].back()["channels"].push_back(channel);
      }
    }
    return doc.dump();
  };
  // Two 600 s channels at 48 kHz: 57.6 M samples (230 MB) from a file of a few hundred bytes.
  REQUIRE_THROWS_WITH(files::readHjif(hjif(1, 2, 48000L * 600), "big.hjif"),
                      Contains("big.hjif: perceptions[0].channels[1].sample_count") && Contains("budget of 48000000 samples"));
  // Channels of every perception count together against the glove's ten actuators.
  REQUIRE_THROWS_WITH(files::readHjif(hjif(3, 4, 48), "many.hjif"),
                      Contains("many.hjif: perceptions[2].channels: 12 vibration channels"));
  CHECK(files::readHjif(hjif(1, 1, 48000L * 600), "one.hjif").channels.size() == 1);  // within the budget
}

TEST_CASE("Playing an HJIF clip reproduces the recorded WAV", "[files][play]") {
  const auto dir = vt::test::outputDir("files_play");
  const auto clip = recordSynthetic(dir);
  files::saveHapticFile(clip, dir / "rec.hjif", false);
  const files::ClipPlayer player(files::loadHapticFile(dir / "rec.hjif"));
  CHECK(player.sampleRate_hz() == kRate_hz);
  CHECK(player.frame(player.tickCount()).intensity[1] == 0.0f);  // silent past the end
  for (int tick : {0, 123, 399, 450}) {
    const ActuatorFrame expected = syntheticFrame(tick);
    const ActuatorFrame got = player.frame(std::uint64_t(tick));
    REQUIRE(got.blockLength == kBlock);
    for (int a = 0; a < 2; ++a) {
      for (int k = 0; k < kBlock; ++k) {
        CHECK(got.block[std::size_t(a)][std::size_t(k)] == Approx(expected.block[std::size_t(a)][std::size_t(k)]).margin(1e-4));
      }
    }
  }
}
