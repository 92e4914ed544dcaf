#pragma once
// The sample rate the codec tests code their signals at: the haptic loop's, 8 kHz.

inline constexpr int kRate = 8000;
