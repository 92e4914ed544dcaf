#pragma once
// The built-in scene: textured plates on a table, every texture generated here so the
// program needs no files. Procedural patterns double as simple vibration maps.
#include "vt/scene/scene.hpp"

namespace vt {

enum class Pattern { Stripes, Checker, Dots, Grid, Wood, Speckle };

/// Height-like value in [0,1] of a pattern at texture coordinate (u,v); deterministic.
float patternValue(Pattern pattern, float u, float v) noexcept;

/// An RGBA8 texture of the pattern blended between two sRGB colours.
Image8 makePatternTexture(Pattern pattern, int size, glm::vec3 colorA, glm::vec3 colorB);

/// A vibration map of the pattern: rough where the pattern changes, in [0,1].
ImageF makePatternVibrationMap(Pattern pattern, int size);

/// A square plate of side `plate_m` at y = 0 (centred on the origin, u along +x) whose
/// vibration map is a stripe grating along x of spatial period `period_m`: each period's first
/// half 1, the second 0, `pixelsPerPeriod` pixels a period; bilinear sampling puts the rising
/// edges exactly at x = -plate_m / 2 + k * period_m. For measuring temporal consistency.
Scene makeGratingPlate(float plate_m, float period_m, int pixelsPerPeriod = 16);

/// Options for the demo scene (`variant` changes it visibly, for golden-test sanity checks).
struct DemoSceneOptions {
  int textureSize = 256;
  int variant = 0;
};

/// The table with four tactile plates; camera framed on the plates.
Scene makeDemoScene(const DemoSceneOptions& options = {});

}  // namespace vt
