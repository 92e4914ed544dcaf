// Haptic files at their limits (issue #27): what export/convert write, play reads back; long clips
// are split; an unknown frequency means the nominal one in every format; the packed JSON reader
// names malformed records; two channels on one actuator are refused.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <numbers>

#include <nlohmann/json.hpp>

#include "test_support.hpp"
#include "vt/core/budgets.hpp"
#include "vt/haptics/files/clip_player.hpp"
#include "vt/haptics/files/haptic_clip.hpp"
#include "vt/haptics/files/haptic_formats.hpp"
#include "vt/haptics/signal_analysis.hpp"
#include "vt/haptics/wav.hpp"

using Catch::Matchers::Contains;
using nlohmann::json;
namespace files = vt::haptics::files;
using vt::haptics::ActuatorId;

namespace {

// An envelope-only clip on the index finger: amplitude swinging 0.2..0.8 every 100 ms at a
// frequency sweeping 80..400 Hz (`unknown`: 0 Hz throughout).
files::HapticClip envelopeClip(double duration_s, bool unknown = false) {
  files::HapticClip clip;
  clip.duration_s = duration_s;
  clip.description = "limits";
  clip.channels.emplace_back();
  clip.channels[0].actuator = ActuatorId::Index;
  for (int i = 0; i * 0.1 <= duration_s + 1e-9; ++i)
    clip.channels[0].envelope.push_back({i * 0.1, i % 2 ? 0.8f : 0.2f, unknown ? 0.0f : 80.0f + float(i % 33) * 10.0f});
  return clip;
}

std::string hjifWithChannels(const std::string& channels) {
  return R"({"version":"2023","profile":"Main","level":1,"date":"2025","description":"","timescale":1000,"avatars":[],
    "syncs":[],"perceptions":[{"id":0,"avatar_id":0,"description":"","perception_modality":"Vibrotactile",
    "effect_library":[],"channels":[)" + channels + "]}]}";
}

std::string channel(const std::string& description, const std::string& part, const std::string& keyframes) {
  return R"({"id":0,"description":")" + description + R"(","gain":1,"mixing_coefficient":1,"body_part_mask":0,
    "body_part_target":["Right","Hand",")" + part + R"("],"bands":[{"band_type":"VectorialWave","lower_frequency_limit":0,
    "upper_frequency_limit":500,"effects":[{"effect_type":"Basis","position":0,"keyframes":[)" + keyframes + "]}]}]}";
}

const std::string kKeyframes = R"({"relative_position":0,"amplitude_modulation":0.5},{"relative_position":100,"amplitude_modulation":0.5})";

}  // namespace

TEST_CASE("Two HJIF channels on one actuator are refused, naming both", "[files][hjif][limits]") {
  REQUIRE_THROWS_WITH(files::readHjif(hjifWithChannels(channel("index", "Index", kKeyframes) + "," + channel("index", "Index", kKeyframes)), "dup.hjif"),
                      Contains("dup.hjif: perceptions[0].channels[0] and channels[1] both play on actuator 'index'"));
  // A body location names the actuator when the description does not.
  REQUIRE_THROWS_WITH(files::readHjif(hjifWithChannels(channel("left one", "Thumb", kKeyframes) + "," + channel("thumb", "Palm", kKeyframes)), "loc.hjif"),
                      Contains("channels[0] and channels[1] both play on actuator 'thumb'"));
  const auto clip = files::readHjif(hjifWithChannels(channel("a", "Middle", kKeyframes) + "," + channel("b", "Palm", kKeyframes)), "ok.hjif");
  REQUIRE(clip.channels.size() == 2);
  CHECK(clip.channels[0].actuator == ActuatorId::Middle);
  CHECK(clip.channels[1].actuator == ActuatorId::Thumb);  // the first actuator no channel claims
}

TEST_CASE("An unknown frequency plays at the nominal frequency from every format", "[files][limits]") {
  const auto dir = vt::test::outputDir("files_unknown_frequency");
  const auto clip = envelopeClip(0.5, true);
  for (const char* ext : {".hjif", ".ahap", ".haptic", ".wav"}) {
    INFO(ext);
    const auto path = dir / (std::string("unknown-index") + ext);
    files::saveHapticFile(clip, path, true);
    const files::ClipPlayer player(files::loadHapticFile(path));
    std::vector<float> wave;
    for (std::uint64_t t = 0; t < player.tickCount(); ++t) {
      const auto frame = player.frame(t);
      wave.insert(wave.end(), frame.block[1].begin(), frame.block[1].begin() + frame.blockLength);
    }
    CHECK(vt::haptics::dominantFrequency_hz(wave, player.sampleRate_hz(), 60, 440) == Approx(vt::haptics::kNominalFrequency_hz).margin(2.0));
  }
  // The normalised scales carry it as their middle, 0.5 (the default of .haptic and OpenXR).
  const json ahap = json::parse(files::writeAhap(clip, 0));
  for (const json& entry : ahap["Pattern"])
    if (entry.contains("ParameterCurve") && entry["ParameterCurve"]["ParameterID"] == "HapticSharpnessControl")
      for (const json& p : entry["ParameterCurve"]["ParameterCurveControlPoints"]) CHECK(p["ParameterValue"].get<double>() == 0.5);
  const json meta = json::parse(files::writeMetaHaptic(clip, 0));
  for (const json& p : meta["signals"]["continuous"]["envelopes"]["frequency"]) CHECK(p["frequency"].get<double>() == 0.5);
  CHECK(vt::haptics::frequencyFromNormalised(0.5f) == vt::haptics::kNominalFrequency_hz);
}

TEST_CASE("Clips at each format's time limit round-trip, longer ones are split into playable parts", "[files][limits]") {
  const auto dir = vt::test::outputDir("files_time_limit");
  for (const char* ext : {".hjif", ".ahap", ".haptic", ".wav"}) {
    INFO(ext);
    const auto whole = envelopeClip(files::kMaxClip_s);
    const auto one = files::saveHapticFile(whole, dir / (std::string("whole") + ext), true);
    REQUIRE(one.size() == 1);
    const auto back = files::loadHapticFile(one[0]);
    CHECK(back.duration_s == Approx(files::kMaxClip_s).margin(0.002));
    CHECK(files::ClipPlayer(back).tickCount() >= 599999u);
    // 1.5 s past the limit: two parts, the second holding the rest.
    const auto longer = envelopeClip(files::kMaxClip_s + 1.5);
    const auto parts = files::saveHapticFile(longer, dir / (std::string("long") + ext), true);
    REQUIRE(parts.size() == 2);
    CHECK(parts[1].filename().string() == std::string("long-part2") + ext);
    const auto second = files::loadHapticFile(parts[1]);
    CHECK(second.duration_s == Approx(1.5).margin(0.002));
    const files::ClipPlayer player(second);
    if (std::string(ext) == ".wav") continue;  // the waveform only: its envelope is checked through play above
    for (double t = 0.05; t < 1.45; t += 0.1)
      CHECK(files::envelopeAt(second.channels[0].envelope, t).amplitude ==
            Approx(files::envelopeAt(longer.channels[0].envelope, files::kMaxClip_s + t).amplitude).margin(0.003));
  }
}

TEST_CASE("An HJIF waveform too large for one file is split into files play reads, sample for sample", "[files][hjif][limits]") {
  // 40 s at 48 kHz: about 1.9 M keyframes, more than 128 MiB of HJIF in one file.
  const auto dir = vt::test::outputDir("files_hjif_bytes");
  files::HapticClip clip;
  clip.sampleRate_hz = 48000;
  clip.duration_s = 40.0;
  clip.channels.emplace_back();
  auto& pcm = clip.channels[0].pcm;
  pcm.resize(48000 * 40);
  for (std::size_t i = 0; i < pcm.size(); ++i) pcm[i] = float(std::sin(double(i) * 0.37) * 0.9 * std::sin(double(i) * 1e-4));
  const auto parts = files::saveHapticFile(clip, dir / "big.hjif", true);
  REQUIRE(parts.size() >= 2);
  std::vector<float> joined;
  for (const auto& part : parts) {
    CHECK(std::filesystem::file_size(part) <= vt::budget::kHapticFileBytes);
    const auto back = files::loadHapticFile(part);
    CHECK(back.duration_s <= files::kMaxClip_s);
    joined.insert(joined.end(), back.channels.at(0).pcm.begin(), back.channels[0].pcm.end());
  }
  REQUIRE(joined.size() == pcm.size());
  // Floats printed in their shortest exact form; samples on the line through their neighbours
  // are left out and interpolated back (within 1e-7 of the line): every sample within 1e-6.
  float worst = 0.0f;
  for (std::size_t i = 0; i < pcm.size(); ++i) worst = std::max(worst, std::fabs(joined[i] - pcm[i]));
  CHECK(worst < 1e-6f);
}

TEST_CASE("The haptic files' JSON reader names malformed records and deep nesting", "[files][limits]") {
  REQUIRE_THROWS_WITH(files::readHjif(hjifWithChannels(channel("index", "Index", R"({"relative_position":0,"amplitude_modulation":0.5},7)")), "rec.hjif"),
                      Contains("rec.hjif: keyframes[1] must be an object"));
  REQUIRE_THROWS_WITH(files::readHjif(hjifWithChannels(channel("index", "Index", R"({"relative_position":0,"amplitude_modulation":"loud"})")), "str.hjif"),
                      Contains("str.hjif: perceptions[0].channels[0].bands[0].effects[0].keyframes[0].amplitude_modulation must be a number"));
  REQUIRE_THROWS_WITH(files::readHjif(hjifWithChannels(channel("index", "Index", R"({"relative_position":0})")), "miss.hjif"),
                      Contains("keyframes[0].amplitude_modulation is missing"));
  REQUIRE_THROWS_WITH(files::readHjif(hjifWithChannels(channel("index", "Index", R"({"other":1})")), "none.hjif"),
                      Contains("none.hjif: keyframes[0] has none of the members read here"));
  const std::string deep = R"({"x":)" + std::string(20000, '[') + std::string(20000, ']') + "}";
  REQUIRE_THROWS_WITH(files::readAhap(deep, "deep.ahap", ActuatorId::Index), Contains("deep.ahap: nested more than 64 levels deep"));
  REQUIRE_THROWS_WITH(files::readAhap("{\"Version\": 1,", "cut.ahap", ActuatorId::Index), Contains("cut.ahap: not valid JSON"));
}

TEST_CASE("A recording longer than a recording may last is refused, naming the limit", "[files][limits]") {
  const auto dir = vt::test::outputDir("files_long_recording");
  std::ofstream(dir / "gap.csv") << "t_ns,sequence,index,index_hz\n0,0,0.5,250\n1000000000000000000,1,0.5,250\n";
  REQUIRE_THROWS_WITH(files::loadRecording(dir / "gap.csv", ""),
                      Contains("gap.csv' line 3") && Contains("past the 3600 s a recording may last"));
}

TEST_CASE("An actuator CSV's numbers beyond a float's range are clamped or refused, never converted", "[files][limits]") {
  // float(1e300) is undefined: the amplitude is clamped as a double, the frequency refused.
  const files::HapticClip clip = files::readActuatorCsv("t_ns,sequence,index,index_hz\n0,0,1e300,250\n1000000,1,-1e300,-1e300\n", "big.csv");
  REQUIRE(clip.channels.size() == 1);
  REQUIRE(clip.channels[0].envelope.size() == 2);
  CHECK(clip.channels[0].envelope[0].amplitude == 1.0f);
  CHECK(clip.channels[0].envelope[1].amplitude == 0.0f);
  CHECK(clip.channels[0].envelope[1].frequency_hz == 0.0f);
  REQUIRE_THROWS_WITH(files::readActuatorCsv("t_ns,sequence,index,index_hz\n0,0,0.5,1e300\n", "fast.csv"),
                      Contains("fast.csv line 2: index_hz 1e+300 Hz is over 100000 Hz"));
  REQUIRE_THROWS_WITH(files::readActuatorCsv("t_ns,sequence,index,index,index_hz,index_hz\n", "twice.csv"),
                      Contains("twice.csv: line 1: actuator 'index' twice"));
}

TEST_CASE("What a reader accepts is written in every format as a file that reads back, or refused naming why", "[files][limits]") {
  // Each found by fuzz_haptic_file's write-back (its seeds replay them).
  // A WAV sample of -32768 (wavSample never writes it) reads as -1, which HJIF's keyframes hold.
  std::string wav = vt::haptics::wavHeader(1, 8000, 2);
  wav += std::string("\x00\x80\xff\x7f", 4);  // -32768, 32767
  const files::HapticClip full = files::readWav(wav, "full-scale.wav");
  REQUIRE(full.channels.size() == 1);
  CHECK(full.channels[0].pcm == std::vector<float>{-1.0f, 1.0f});
  CHECK(files::readHjif(files::writeHjif(full), "written").channels.at(0).pcm == full.channels[0].pcm);
  // A one-line recording spans no time: AHAP and .haptic write it as one 1 ms tick.
  const files::HapticClip tick = files::readActuatorCsv("t_ns,sequence,index,index_hz\n5,0,0.25,250\n", "tick.csv");
  REQUIRE(tick.duration_s == 0.0);
  const files::HapticClip ahap = files::readAhap(files::writeAhap(tick, 0), "written", ActuatorId::Index);
  CHECK(ahap.duration_s == Approx(0.001));
  CHECK(ahap.channels.at(0).envelope.at(0).amplitude == Approx(0.25f));
  CHECK(files::readMetaHaptic(files::writeMetaHaptic(tick, 0), "written", ActuatorId::Index).duration_s == Approx(0.001));
  // One envelope point, at the clip's end (an HJIF channel's one keyframe): .haptic holds its level from 0.
  files::HapticClip late = envelopeClip(0.5);
  late.channels[0].envelope = {{0.5, 0.3f, 120.0f}};
  const files::HapticClip meta = files::readMetaHaptic(files::writeMetaHaptic(late, 0), "written", ActuatorId::Index);
  CHECK(meta.duration_s == Approx(0.5));
  CHECK(files::envelopeAt(meta.channels.at(0).envelope, 0.0).amplitude == Approx(0.3f));
  // Silent at 16 bits: readWav has nothing to play, so writeWav refuses before writing.
  const files::HapticClip faint = files::readActuatorCsv("t_ns,sequence,index,index_hz\n0,0,0.00001,250\n1000000,1,0,250\n", "faint.csv");
  REQUIRE_THROWS_WITH(files::writeWav(faint), Contains("every channel of the clip is silent at 16 bits"));
  // A CSV with no tick, or whose frequency columns do not name its actuators, is refused.
  REQUIRE_THROWS_WITH(files::readActuatorCsv("t_ns,sequence,index,index_hz\n", "empty.csv"),
                      Contains("empty.csv: no line after the header"));
  REQUIRE_THROWS_WITH(files::readActuatorCsv("t_ns,sequence,thumb,in\n0,0,0.5,250\n", "cut.csv"),
                      Contains("cut.csv: line 1: column 4 is 'in', expected 'thumb_hz'"));
}

TEST_CASE("Conversions state what the target format cannot carry", "[files][limits]") {
  files::HapticClip pcm;
  pcm.sampleRate_hz = 8000;
  pcm.duration_s = 0.1;
  pcm.channels.emplace_back();
  pcm.channels[0].pcm.assign(800, 0.25f);
  CHECK(files::conversionLosses(pcm, files::HapticFormat::Hjif).empty());
  CHECK_THAT(files::conversionLosses(pcm, files::HapticFormat::Ahap).at(0), Contains("waveform is not carried"));
  CHECK_THAT(files::conversionLosses(pcm, files::HapticFormat::Wav).at(0), Contains("16 bits"));
  CHECK_THAT(files::conversionLosses(envelopeClip(1.0), files::HapticFormat::Wav).at(0), Contains("synthesised sine"));
  auto high = envelopeClip(1.0);
  high.channels[0].envelope[3].frequency_hz = 480.0f;  // above the normalised scale
  CHECK_THAT(files::conversionLosses(high, files::HapticFormat::Ahap).back(), Contains("clamped"));
}
