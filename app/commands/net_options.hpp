#pragma once
// Command-line options shared by `vtouching serve` and `vtouching client`.
#include <string>
#include <vector>

#include "cli.hpp"
#include "vt/core/error.hpp"
#include "vt/haptics/codec/codec.hpp"
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

/// --loss P, --delay-ms MS, --jitter-ms MS, --reorder P: in-process impairment of what this
/// side receives (tests and demos; netem does the same on a real link, docs/protocol.md).
inline net::Impairment impairmentOptions(cli::Args& args) {
  net::Impairment impairment;
  impairment.loss = args.doubleOr("loss", 0.0);
  impairment.delay_ns = std::int64_t(args.doubleOr("delay-ms", 0.0) * 1e6);
  impairment.jitter_ns = std::int64_t(args.doubleOr("jitter-ms", 0.0) * 1e6);
  impairment.reorder = args.doubleOr("reorder", 0.0);
  if (!(impairment.loss >= 0.0 && impairment.loss <= 1.0)) fail("--loss expects a probability 0..1");
  if (!(impairment.reorder >= 0.0 && impairment.reorder <= 1.0)) fail("--reorder expects a probability 0..1");
  if (impairment.delay_ns < 0) fail("--delay-ms must not be negative");
  if (impairment.jitter_ns < 0) fail("--jitter-ms must not be negative");
  return impairment;
}

}  // namespace vt::app
