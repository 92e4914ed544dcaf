#include "vt/haptics/devices/audio_output.hpp"

#include <alsa/asoundlib.h>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>

#include "waveform_resampler.hpp"
#include "vt/core/error.hpp"
#include "vt/core/log.hpp"

namespace vt::haptics {
namespace {

constexpr std::int64_t kErrorRetry_ns = 100'000'000;

// ALSA prints its own diagnostics on stderr ("ALSA lib confmisc.c:...: cannot find card '0'",
// eight lines for a missing card) before the one line this output's error says: they go to the
// debug log instead (VT_LOG=debug shows them).
void alsaDiagnostic(const char* file, int line, const char* function, int err, const char* format, ...) {
  if (log::level() > log::Level::Debug) return;
  char text[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(text, sizeof text, format, args);
  va_end(args);
  log::debug("ALSA ", file, ":", line, " (", function, "): ", text, err ? str(": ", snd_strerror(err)) : std::string());
}

void quietAlsa() {
  static const bool installed = (snd_lib_error_set_handler(alsaDiagnostic), true);
  (void)installed;
}

std::vector<int> defaultChannels(int actuators) {
  std::vector<int> channels(std::size_t(std::clamp(actuators, 1, kMaxActuators)));
  for (std::size_t c = 0; c < channels.size(); ++c) channels[c] = int(c);
  return channels;
}

}  // namespace

std::vector<int> parseChannelMap(std::string_view text) {
  std::vector<int> channels;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string_view name = text.substr(start, comma - start);
    int actuator = -2;
    if (name == "-") actuator = -1;
    else if (const auto id = actuatorFromName(name)) actuator = int(*id);  // "pinky" too, as older maps said
    if (actuator == -2) {
      std::string known;
      for (int a = 0; a < kMaxActuators; ++a) known += str(a ? "|" : "", actuatorName(ActuatorId(a)));
      fail("--channels: entry ", channels.size() + 1, " '", name, "' is not an actuator (", known, "|-)");
    }
    channels.push_back(actuator);
    start = comma + 1;
  }
  if (channels.size() > 64) fail("--channels: ", channels.size(), " channels, at most 64");
  return channels;
}

std::vector<AudioDeviceInfo> listAudioDevices() {
  std::vector<AudioDeviceInfo> devices;
  quietAlsa();
  void** hints = nullptr;
  if (snd_device_name_hint(-1, "pcm", &hints) < 0) return devices;
  for (void** h = hints; *h; ++h) {
    char* name = snd_device_name_get_hint(*h, "NAME");
    char* desc = snd_device_name_get_hint(*h, "DESC");
    char* io = snd_device_name_get_hint(*h, "IOID");
    if (name && (!io || std::string_view(io) == "Output")) {
      std::string description = desc ? desc : "";
      std::replace(description.begin(), description.end(), '\n', ' ');
      devices.push_back({name, description});
    }
    std::free(name);
    std::free(desc);
    std::free(io);
  }
  snd_device_name_free_hint(hints);
  std::stable_partition(devices.begin(), devices.end(), [](const AudioDeviceInfo& d) { return d.name == "default"; });
  return devices;
}

struct AudioOutput::Device {
  snd_pcm_t* pcm = nullptr;  // null while a failed device waits to be opened anew
  std::vector<int> channels;
  unsigned rate_hz = 0;
  snd_pcm_uframes_t period = 0, buffer = 0;  // the first open's: the stream keeps them
  std::atomic<bool> clocked{true};
  std::unique_ptr<detail::WaveformResampler> resampler;
  ~Device() { close(); }
  void close() noexcept {
    if (pcm) snd_pcm_close(pcm);
    pcm = nullptr;
  }
};

namespace {

enum class OpenStep { Open, Params, ReadParams };

/// Opens `name` for playback as the output streams it (S16 interleaved, what every device and
/// plug layer takes; ALSA converts where the hardware differs). 0, or ALSA's error and the step
/// that failed. Any thread.
int openPcm(const std::string& name, unsigned channels, const AudioOutputConfig& config, snd_pcm_t*& pcm,
            snd_pcm_uframes_t& buffer, snd_pcm_uframes_t& period, OpenStep& step) noexcept {
  step = OpenStep::Open;
  if (int e = snd_pcm_open(&pcm, name.c_str(), SND_PCM_STREAM_PLAYBACK, 0); e < 0) {
    pcm = nullptr;
    return e;
  }
  step = OpenStep::Params;
  int e = snd_pcm_set_params(pcm, SND_PCM_FORMAT_S16_LE, SND_PCM_ACCESS_RW_INTERLEAVED, channels, config.rate_hz, 1,
                             config.latency_us);
  if (e >= 0) {
    step = OpenStep::ReadParams;
    e = snd_pcm_get_params(pcm, &buffer, &period);
  }
  if (e < 0) {
    snd_pcm_close(pcm);
    pcm = nullptr;
  }
  return e;
}

}  // namespace

AudioOutput::AudioOutput(AudioOutputConfig config, const Clock& clock)
    : QueuedOutput(clock, config.failsafe, config.heartbeat, 256), m_config(std::move(config)),
      m_device(std::make_unique<Device>()) {
  Device& d = *m_device;
  d.channels = m_config.channels.empty() ? defaultChannels(m_config.actuators) : m_config.channels;
  const std::string& name = m_config.device;
  quietAlsa();
  OpenStep step;
  if (int e = openPcm(name, unsigned(d.channels.size()), m_config, d.pcm, d.buffer, d.period, step); e < 0) {
    switch (step) {
      case OpenStep::Open:
        fail("audio device '", name, "': cannot open for playback: ", snd_strerror(e), " (vtouching devices lists them)");
      case OpenStep::Params:  // "plughw:" rather than "hw:" for cards with other native formats
        fail("audio device '", name, "': ", d.channels.size(), " channels at ", m_config.rate_hz, " Hz with ",
             m_config.latency_us, " us latency refused: ", snd_strerror(e));
      case OpenStep::ReadParams:
        fail("audio device '", name, "': reading buffer parameters failed: ", snd_strerror(e));
    }
  }
  d.rate_hz = m_config.rate_hz;
  // Input jitter buffer: as long as the device buffer (at least 2 ms), so a loop tick that comes
  // up to that late still finds the stream fed.
  const double prefill_s = std::max(2e-3, double(d.buffer) / double(d.rate_hz));
  d.resampler = std::make_unique<detail::WaveformResampler>(d.channels, d.rate_hz, int(std::ceil(prefill_s * 8000.0)));
  log::info("audio: '", name, "' ", d.channels.size(), " channels at ", d.rate_hz, " Hz, period ", d.period,
            " frames, buffer ", d.buffer, " frames");
  startWriter("audio output");
}

AudioOutput::~AudioOutput() { stop(); }  // the writer's last act is silence, drained

std::string AudioOutput::name() const { return "audio " + m_config.device; }

std::int64_t AudioOutput::latency_ns() const {
  // A sample written now plays once the device buffer ahead of it has played.
  return m_device->rate_hz ? std::int64_t(m_device->buffer) * 1'000'000'000 / std::int64_t(m_device->rate_hz) : 0;
}

std::string AudioOutput::statusLine() const {
  const AudioOutputStatus s = status();
  return str("audio ", s.device, " ", s.channels, " ch ", s.rate_hz, " Hz, buffer ", s.buffer_frames, ", underruns ",
             s.underruns, ", starved ", s.starvedFrames, ", skipped ", s.skippedSamples, failsafeNote(s.failsafe),
             s.reopens ? str(", reopened ", s.reopens, "x") : std::string(),
             s.lastError.empty() ? std::string() : ", " + s.lastError);
}

AudioOutputStatus AudioOutput::status() const {
  AudioOutputStatus s;
  s.device = m_config.device;
  s.rate_hz = m_device->rate_hz;
  s.channels = unsigned(m_device->channels.size());
  s.period_frames = unsigned(m_device->period);
  s.buffer_frames = unsigned(m_device->buffer);
  s.clocked = m_device->clocked.load();
  s.framesWritten = m_framesWritten.load();
  s.underruns = m_underruns.load();
  s.starvedFrames = m_starved.load();
  s.skippedSamples = m_skipped.load();
  s.queueDropped = m_queue.dropped();
  s.reopens = m_reopens.load();
  s.failsafe = m_failsafe.lastReason();
  s.lastError = lastError();
  return s;
}

void AudioOutput::writerLoop() noexcept {
  Device& d = *m_device;
  const std::size_t channels = d.channels.size();
  std::vector<float> mix(std::size_t(d.period) * channels);
  std::vector<std::int16_t> pcm(mix.size());
  std::uint64_t popped = 0, written = 0;
  std::int64_t anchor_ns = m_clock.now_ns();
  std::uint64_t anchorWritten = 0;
  bool clockKnown = false;
  ActuatorFrame frame;
  while (true) {
    const bool ending = stopping();
    while (m_queue.pop(frame)) {
      ++popped;
      d.resampler->push(frame);
    }
    if (ending || m_failsafe.evaluate(heartbeat(popped)) != FailsafeReason::None) {
      d.resampler->reset();
      std::fill(mix.begin(), mix.end(), 0.0f);
    } else {
      d.resampler->render(mix);
    }
    for (std::size_t i = 0; i < mix.size(); ++i) pcm[i] = std::int16_t(std::lround(std::clamp(mix[i], -1.0f, 1.0f) * 32767.0f));
    m_starved.store(d.resampler->starvedFrames(), std::memory_order_relaxed);
    m_skipped.store(d.resampler->skippedSamples(), std::memory_order_relaxed);

    // A device that takes samples as fast as they come (null, file) has no clock to block on:
    // the steady clock paces it, a buffer ahead, as a real device would.
    if (!d.clocked.load(std::memory_order_relaxed)) {
      const std::int64_t ahead = std::int64_t(written - anchorWritten) - std::int64_t(d.buffer);
      if (ahead > 0) m_clock.sleepUntil(anchor_ns + ahead * 1'000'000'000 / std::int64_t(d.rate_hz));
    }
    snd_pcm_sframes_t n = snd_pcm_writei(d.pcm, pcm.data(), d.period);
    if (n == -EPIPE) {
      m_underruns.fetch_add(1, std::memory_order_relaxed);
      snd_pcm_prepare(d.pcm);
      n = snd_pcm_writei(d.pcm, pcm.data(), d.period);
    }
    if (n < 0) n = snd_pcm_recover(d.pcm, int(n), 1);
    if (n < 0) {
      setLastError("write failed", snd_strerror(int(n)));
      if (ending) break;
      // Some handles stay failed (a USB interface unplugged, then plugged back): the device is
      // opened anew, once a retry period until it takes the stream, the loop's frames dropped
      // meanwhile. The stream keeps the first open's period and buffer.
      d.close();
      while (!d.pcm && !stopping()) {
        m_clock.sleepUntil(m_clock.now_ns() + kErrorRetry_ns);
        while (m_queue.pop(frame)) ++popped;
        snd_pcm_uframes_t buffer = 0, period = 0;
        OpenStep step;
        if (const int e = openPcm(m_config.device, unsigned(channels), m_config, d.pcm, buffer, period, step); e < 0)
          setLastError("reopen failed", snd_strerror(e));
      }
      if (!d.pcm) break;
      m_reopens.fetch_add(1, std::memory_order_relaxed);
      d.resampler->reset();
      anchor_ns = m_clock.now_ns();
      anchorWritten = written;
      clockKnown = false;
      d.clocked.store(true);
      continue;
    }
    written += std::uint64_t(n);
    m_framesWritten.store(written, std::memory_order_relaxed);
    if (!clockKnown && written - anchorWritten >= 4 * d.buffer) {
      // A clocked device blocked for about (frames since the anchor - buffer) frames of time by now.
      clockKnown = true;
      const std::int64_t elapsed_ns = m_clock.now_ns() - anchor_ns;
      const std::int64_t played_ns =
          std::int64_t(written - anchorWritten - d.buffer) * 1'000'000'000 / std::int64_t(d.rate_hz);
      if (elapsed_ns < played_ns / 2) {
        d.clocked.store(false);
        anchor_ns = m_clock.now_ns();
        anchorWritten = written - d.buffer;  // from now on, as if its buffer were full
      }
    }
    if (ending) break;
  }
  // The stream ends on at least a device buffer and 20 ms of silence, so whatever the device
  // still queued is followed by zeros long enough for an amplifier to settle; then it plays out.
  if (!d.pcm) return;  // stopped while the device was away
  std::fill(pcm.begin(), pcm.end(), std::int16_t(0));
  const std::uint64_t tail = std::max<std::uint64_t>(std::uint64_t(d.buffer), std::uint64_t(d.rate_hz) / 50);
  for (std::uint64_t zeros = 0; zeros < tail; zeros += std::uint64_t(d.period))
    if (snd_pcm_writei(d.pcm, pcm.data(), d.period) < 0) break;
  snd_pcm_drain(d.pcm);
}

}  // namespace vt::haptics
