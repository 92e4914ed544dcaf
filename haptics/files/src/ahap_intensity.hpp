#pragma once
// Core Haptics plays an intensity curve (intensity = sqrt(amplitude)) interpolated linearly between
// its control points; between two envelope points of amplitudes a0 and a1 that plays
// s(1-s)(sqrt a1 - sqrt a0)^2 below the envelope's straight line (s: the fraction of the way), up
// to a quarter of (sqrt a1 - sqrt a0)^2 at the middle: 0.25 from silence to full. The writer
// inserts points equally spaced in intensity, no closer than the glove's 1 ms tick (a waveform's
// 1 ms peaks are written as they are), and the part sizing counts them.
namespace vt::haptics::files {

/// Largest amplitude error the inserted points leave between two envelope points.
inline constexpr double kAhapInterpolationError = 0.001;

/// Pieces the segment from amplitude a0 to a1, `duration_s` long, is cut into (1: no point
/// inserted).
int ahapIntensityPieces(float a0, float a1, double duration_s) noexcept;

}  // namespace vt::haptics::files
