// The tactile stream codec over numpy arrays: a waveform (frames, channels) <-> packets.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "vt/core/error.hpp"
#include "vt/haptics/codec/stream_codec.hpp"

namespace py = pybind11;

namespace vt::python {
namespace {

haptics::CodecConfig codecConfig(const std::string& codec, int quality, int channels, int sampleRate_hz, int block_ms) {
  haptics::CodecConfig config;
  if (!haptics::parseCodecName(codec, config.id)) fail("codec: unknown codec '", codec, "'");
  config.quality = quality;
  config.channels = channels;
  config.sampleRate_hz = sampleRate_hz;
  config.block_ms = block_ms;
  if (const auto problem = haptics::checkCodecConfig(config); !problem.empty()) fail("codec: ", problem);
  return config;
}

}  // namespace

void bindCodec(py::module_& m) {
  m.def("encode",
        [](const py::array_t<float, py::array::c_style | py::array::forcecast>& samples, const std::string& codec, int quality,
           int sampleRate_hz, int block_ms) {
          if (samples.ndim() != 2) fail("encode: expected a (samples, channels) array");
          const auto config = codecConfig(codec, quality, int(samples.shape(1)), sampleRate_hz, block_ms);
          const auto encoder = haptics::makeBlockEncoder(config);
          const auto frames = std::size_t(samples.shape(0)) / std::size_t(config.frameLength);
          if (std::size_t(samples.shape(0)) % std::size_t(config.frameLength))
            fail("encode: ", samples.shape(0), " samples is not a whole number of ", config.frameLength, "-sample frames");
          py::list packets;
          haptics::WaveBlock block{};
          for (std::size_t f = 0; f < frames; ++f) {
            for (int c = 0; c < config.channels; ++c)
              for (int s = 0; s < config.frameLength; ++s)
                block[std::size_t(c)][std::size_t(s)] = samples.at(py::ssize_t(f) * config.frameLength + s, c);
            if (encoder->push(block)) {
              const auto p = encoder->packet();
              packets.append(py::bytes(reinterpret_cast<const char*>(p.data()), p.size()));
            }
          }
          if (encoder->flush()) {
            const auto p = encoder->packet();
            packets.append(py::bytes(reinterpret_cast<const char*>(p.data()), p.size()));
          }
          return packets;
        },
        py::arg("samples"), py::arg("codec") = "perceptual", py::arg("quality") = 50, py::arg("sample_rate_hz") = 8000,
        py::arg("block_ms") = 4, "Encodes a (samples, channels) waveform into codec packets (bytes), as the server sends them.");
  m.def("decode",
        [](const std::vector<py::bytes>& packets, int channels, const std::string& codec, int quality, int sampleRate_hz,
           int block_ms) {
          const auto config = codecConfig(codec, quality, channels, sampleRate_hz, block_ms);
          const auto decoder = haptics::makeBlockDecoder(config);
          const auto perPacket = std::size_t(decoder->frameCount()) * std::size_t(config.frameLength);
          py::array_t<float> out({py::ssize_t(packets.size() * perPacket), py::ssize_t(channels)});
          auto view = out.mutable_unchecked<2>();
          for (std::size_t p = 0; p < packets.size(); ++p) {
            const std::string_view bytes = packets[p];
            if (!decoder->decode(std::span(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size())))
              fail("decode: packet ", p, " is not a block of this codec configuration");
            for (int f = 0; f < decoder->frameCount(); ++f)
              for (int c = 0; c < channels; ++c)
                for (int s = 0; s < config.frameLength; ++s)
                  view(py::ssize_t(p * perPacket) + f * config.frameLength + s, c) = decoder->frame(f)[std::size_t(c)][std::size_t(s)];
          }
          return out;
        },
        py::arg("packets"), py::arg("channels"), py::arg("codec") = "perceptual", py::arg("quality") = 50,
        py::arg("sample_rate_hz") = 8000, py::arg("block_ms") = 4, "Decodes codec packets back into a (samples, channels) waveform.");
}

}  // namespace vt::python
