#pragma once
// XR_FB_haptic_pcm and XR_FB_haptic_amplitude_envelope as the OpenXR registry defines them
// (Debian 12's OpenXR headers, 1.0.20, predate both). Header only: vt::xr sends them and xrsim
// implements them. A newer openxr.h that has them wins.
#include <openxr/openxr.h>

#ifndef XR_FB_haptic_amplitude_envelope
#define XR_FB_haptic_amplitude_envelope 1
#define XR_FB_haptic_amplitude_envelope_SPEC_VERSION 1
#define XR_FB_HAPTIC_AMPLITUDE_ENVELOPE_EXTENSION_NAME "XR_FB_haptic_amplitude_envelope"
#define XR_MAX_HAPTIC_AMPLITUDE_ENVELOPE_SAMPLES_FB 4000u
#define XR_TYPE_HAPTIC_AMPLITUDE_ENVELOPE_VIBRATION_FB XrStructureType(1000173001)
/// Amplitudes 0..1 spread evenly over `duration`.
struct XrHapticAmplitudeEnvelopeVibrationFB {
  XrStructureType type;
  const void* next;
  XrDuration duration;
  uint32_t amplitudeCount;
  const float* amplitudes;
};
#endif

#ifndef XR_FB_haptic_pcm
#define XR_FB_haptic_pcm 1
#define XR_FB_haptic_pcm_SPEC_VERSION 1
#define XR_FB_HAPTIC_PCM_EXTENSION_NAME "XR_FB_haptic_pcm"
#define XR_MAX_HAPTIC_PCM_BUFFER_SIZE_FB 4000
#define XR_TYPE_HAPTIC_PCM_VIBRATION_FB XrStructureType(1000209001)
#define XR_TYPE_DEVICE_PCM_SAMPLE_RATE_STATE_FB XrStructureType(1000209002)
/// A PCM buffer (-1..1) at `sampleRate`, played after what is queued when `append`.
struct XrHapticPcmVibrationFB {
  XrStructureType type;
  const void* next;
  uint32_t bufferSize;
  const float* buffer;
  float sampleRate;
  XrBool32 append;
  uint32_t* samplesConsumed;
};
/// The device's own PCM rate (xrGetDeviceSampleRateFB).
struct XrDevicePcmSampleRateStateFB {
  XrStructureType type;
  void* next;
  float sampleRate;
};
using XrDevicePcmSampleRateGetInfoFB = XrDevicePcmSampleRateStateFB;
typedef XrResult(XRAPI_PTR* PFN_xrGetDeviceSampleRateFB)(XrSession, const XrHapticActionInfo*, XrDevicePcmSampleRateGetInfoFB*);
#endif
