#pragma once
// Command-line options shared by `vtouching serve` and `vtouching client`.
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cli.hpp"
#include "vt/core/error.hpp"
#include "vt/haptics/codec/stream_codec.hpp"
#include "vt/net/auth.hpp"
#include "vt/net/transport.hpp"

namespace vt::app {

/// "perceptual,pcm16,raw-f32" -> codec ids in that order; throws naming the bad entry.
inline std::vector<haptics::CodecId> parseCodecList(const std::string& text) {
  std::vector<haptics::CodecId> ids;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string name = text.substr(start, comma - start);
    haptics::CodecId id{};
    if (!haptics::parseCodecName(name, id)) fail("codec '", name, "' unknown (perceptual, pcm16, raw-f32)");
    ids.push_back(id);
    start = comma + 1;
  }
  return ids;
}

/// --block-ms N: the tactile codec block, one of haptics::kCodecBlockLengths_ms; none without it.
inline std::optional<int> blockLengthOption(cli::Args& args) {
  const auto text = args.value("block-ms");
  if (!text) return std::nullopt;
  const auto& lengths = haptics::kCodecBlockLengths_ms;
  for (int block_ms : lengths)
    if (*text == std::to_string(block_ms)) return block_ms;
  fail("--block-ms ", *text, " is not one of 4, 8, 16, 32, 64, 128");
}

/// --loss P, --delay-ms MS, --jitter-ms MS, --reorder P: in-process impairment of what this
/// side receives (tests and demos; netem does the same on a real link, docs/protocol.md).
inline net::Impairment impairmentOptions(cli::Args& args) {
  net::Impairment impairment;
  impairment.loss = args.doubleOr("loss", 0.0);
  const double delay_ms = args.doubleOr("delay-ms", 0.0);
  const double jitter_ms = args.doubleOr("jitter-ms", 0.0);
  impairment.reorder = args.doubleOr("reorder", 0.0);
  if (!(impairment.loss >= 0.0 && impairment.loss <= 1.0)) fail("--loss expects a probability 0..1");
  if (!(impairment.reorder >= 0.0 && impairment.reorder <= 1.0)) fail("--reorder expects a probability 0..1");
  // Checked as numbers, before the conversion to nanoseconds (1e300 ms would wrap to a negative).
  constexpr double kMaxImpairment_ms = 10'000.0;
  if (!(delay_ms >= 0.0 && delay_ms <= kMaxImpairment_ms)) fail("--delay-ms ", delay_ms, " out of range 0..", kMaxImpairment_ms);
  if (!(jitter_ms >= 0.0 && jitter_ms <= kMaxImpairment_ms)) fail("--jitter-ms ", jitter_ms, " out of range 0..", kMaxImpairment_ms);
  impairment.delay_ns = std::int64_t(delay_ms * 1e6);
  impairment.jitter_ns = std::int64_t(jitter_ms * 1e6);
  return impairment;
}

/// serve --key FILE: the shared key in FILE; when FILE does not exist a new key is written
/// there (owner-only) and printed, to be given to the clients. None without the option.
inline std::optional<net::Key> serverKeyOption(cli::Args& args) {
  const auto path = args.value("key");
  if (!path) return std::nullopt;
  if (std::filesystem::exists(*path)) return net::readKeyFile(*path);
  const net::Key key = net::generateKey();
  net::writeKeyFile(*path, key);
  std::printf("new session key written to %s: %s (clients: --key %s or --key <that hex>)\n", path->c_str(),
              net::keyToHex(key).c_str(), path->c_str());
  return key;
}

/// client --key FILE|HEX: the server's shared key. None without the option.
inline std::optional<net::Key> clientKeyOption(cli::Args& args) {
  const auto text = args.value("key");
  if (!text) return std::nullopt;
  return net::keyFromArgument(*text);
}

}  // namespace vt::app
