#pragma once
// XR_EXT_haptic_parametric (registered extension 776, revision 1, first published in the OpenXR
// 1.1.60 specification, 2026-05-20; not ratified), transcribed from the registry (xr.xml) and the
// extension's chapter: Debian 12's OpenXR headers (1.0.20) predate it. Header only: vt::xr sends
// it and xrsim implements it. A newer openxr.h that has it wins.
#include <openxr/openxr.h>

#ifndef XR_EXT_haptic_parametric
#define XR_EXT_haptic_parametric 1
#define XR_EXT_haptic_parametric_SPEC_VERSION 1
#define XR_EXT_HAPTIC_PARAMETRIC_EXTENSION_NAME "XR_EXT_haptic_parametric"
/// Most amplitude points, frequency points or transients in one xrApplyHapticFeedback call.
#define XR_HAPTIC_PARAMETRIC_MAX_POINTS_TRANSIENTS_EXT 500
/// How long a stream whose next frame is late keeps its last values before it stops (ns).
#define XR_HAPTIC_PARAMETRIC_VIBRATION_EXTEND_DURATION_EXT 50000000
#define XR_HAPTIC_PARAMETRIC_FREQUENCY_MIN_HZ_EXT 1
#define XR_HAPTIC_PARAMETRIC_FREQUENCY_MAX_HZ_EXT 1000
// XrStructureType values: 1000000000 + (776 - 1) * 1000 + offset.
#define XR_TYPE_HAPTIC_PARAMETRIC_VIBRATION_EXT XrStructureType(1000775000)
#define XR_TYPE_HAPTIC_PARAMETRIC_PROPERTIES_EXT XrStructureType(1000775001)
#define XR_TYPE_SYSTEM_HAPTIC_PARAMETRIC_PROPERTIES_EXT XrStructureType(1000775002)

/// Whether one haptic call is a whole event (NONE) or a frame of a stream.
enum XrHapticParametricStreamFrameTypeEXT {
  XR_HAPTIC_PARAMETRIC_STREAM_FRAME_TYPE_NONE_EXT = 0,
  XR_HAPTIC_PARAMETRIC_STREAM_FRAME_TYPE_FIRST_FRAME_EXT = 1,
  XR_HAPTIC_PARAMETRIC_STREAM_FRAME_TYPE_INTERMEDIATE_FRAME_EXT = 2,
  XR_HAPTIC_PARAMETRIC_STREAM_FRAME_TYPE_LAST_FRAME_EXT = 3,
  XR_HAPTIC_PARAMETRIC_STREAM_FRAME_TYPE_MAX_ENUM_EXT = 0x7FFFFFFF
};
/// Chained to XrSystemProperties: whether the system can play parametric haptics.
struct XrSystemHapticParametricPropertiesEXT {
  XrStructureType type;
  void* next;
  XrBool32 supportsParametricHaptics;
};
/// One haptic element's streaming timing and frequency range.
struct XrHapticParametricPropertiesEXT {
  XrStructureType type;
  void* next;
  XrDuration idealFrameSubmissionRate;
  XrDuration minimumFirstFrameDuration;
  float minFrequencyHz;
  float maxFrequencyHz;
};
/// An amplitude or frequency point: `value` 0..1 from `time` (ns since the event started) on.
struct XrHapticParametricPointEXT {
  XrDuration time;
  float value;
};
/// A short click at `time`.
struct XrHapticParametricTransientEXT {
  XrDuration time;
  float amplitude;
  float frequency;
};
/// The haptic event (or one frame of a stream): curves interpolated linearly by the runtime.
struct XrHapticParametricVibrationEXT {
  XrStructureType type;
  const void* next;
  uint32_t amplitudePointCount;
  const XrHapticParametricPointEXT* amplitudePoints;
  uint32_t frequencyPointCount;
  const XrHapticParametricPointEXT* frequencyPoints;
  uint32_t transientCount;
  const XrHapticParametricTransientEXT* transients;
  float minFrequencyHz;
  float maxFrequencyHz;
  XrHapticParametricStreamFrameTypeEXT streamFrameType;
};
typedef XrResult(XRAPI_PTR* PFN_xrHapticParametricGetPropertiesEXT)(XrSession, const XrHapticActionInfo*,
                                                                      XrHapticParametricPropertiesEXT*);
#endif
