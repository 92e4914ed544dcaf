#pragma once
// Every size that comes from input has a budget, checked before allocating; the error names the
// file, the field and the limit. One table here, explained in docs/RELIABILITY.md.
#include <cstddef>
#include <cstdint>

namespace vt::budget {

/// Any image file (PNG/JPEG/...) on disk.
inline constexpr std::uintmax_t kImageFileBytes = 256u << 20;
/// Decoded image: width and height each at most this...
inline constexpr int kImageSide_px = 16384;
/// ...and at most this many pixels (a 32-megapixel photo fits; 16-bit RGBA decode = 256 MiB).
inline constexpr long long kImagePixels = 1LL << 25;
/// A glTF/GLB file, and the buffer and image files it references, all of them together (40
/// buffers naming one 64 MiB file are 2.5 GiB read).
inline constexpr std::uintmax_t kSceneFileBytes = 512u << 20;
/// Node visits while flattening one glTF scene (a node listed as a child many times counts each time).
inline constexpr std::uint64_t kSceneNodeVisits = 100000;
/// Vertices and indices across every mesh instance of one glTF scene (each node using a mesh gets
/// its own copy): 8 Mi vertices (256 MiB) and 32 Mi indices (128 MiB), checked before copying.
inline constexpr std::uint64_t kSceneVertices = 1u << 23;
inline constexpr std::uint64_t kSceneIndices = 1u << 25;
/// JSON nesting (arrays and objects) in any JSON input, checked before a parser runs: parsers and
/// the code walking their trees recurse once per level (a glTF nesting 20,000 arrays in its
/// extras overflowed the stack).
inline constexpr int kJsonDepth = 64;
/// JSON values (numbers, strings, ... each counted) in a glTF's JSON: tinygltf's trees take
/// about 180 bytes per value, so 1 Mi values stay within ~190 MB whatever the file holds.
inline constexpr std::uint64_t kGltfJsonValues = 1u << 20;
/// JSON and CSV descriptions (scan.json, NAME_map.json, calibration points, trajectories, --gains).
inline constexpr std::uintmax_t kTextFileBytes = 64u << 20;
/// One robot or accelerometer log (one scan line).
inline constexpr std::uintmax_t kScanLogBytes = 1u << 30;
/// Taxel bins along one scan line (span / taxel size).
inline constexpr double kTaxelsPerLine = 1e6;
/// Scripted trajectory duration (1 kHz ticks, traces streamed to disk).
inline constexpr double kTrajectoryDuration_s = 3600.0;
/// A time from outside (a trajectory sample's, a recording's stamps, a peer's clock readings),
/// either sign: 2^61 ns (73 years) leaves room to add offsets and subtract two stamps in 64 bits;
/// Unix times (1.8e9 s in 2026) fit until 2043.
inline constexpr std::int64_t kStampTime_ns = std::int64_t(1) << 61;
inline constexpr double kStampTime_s = double(kStampTime_ns) * 1e-9;
/// Contact samples per finger kept for the touch figure (longer runs are decimated to fit).
inline constexpr std::size_t kFigureSamplesPerFinger = 1u << 17;
/// A haptic file (.hjif/.ahap/.haptic) and an actuator recording (--record-csv, --record-wav) read
/// back: a 600 s recording (the longest clip played) of 10 actuators at 8 kHz is a 96 MB WAV.
inline constexpr std::uintmax_t kHapticFileBytes = 128u << 20;
/// One line of a recording, and a path inside one.
inline constexpr std::size_t kRecordingLineBytes = 1u << 16;
inline constexpr std::size_t kPathBytes = 4096;

}  // namespace vt::budget
