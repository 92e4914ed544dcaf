#pragma once
// Factories of the concrete codecs (codec.cpp picks one by id).
#include <memory>

#include "vt/haptics/codec/codec.hpp"

namespace vt::haptics::codec {

std::unique_ptr<TactileCodec> makeRawFloat32();
std::unique_ptr<TactileCodec> makePcm16();
std::unique_ptr<TactileCodec> makePerceptual(int quality);

}  // namespace vt::haptics::codec
