#pragma once
// xrsim settings: environment variables, optionally a JSON file (XRSIM_CONFIG) underneath them.
#include <cstdint>
#include <filesystem>
#include <string>

namespace xrsim {

/// Failure modes a test can ask for, to exercise an application's fallback paths.
enum class Failure { None, NoHmd, RefuseSession };

/// Everything configurable; read once per xrCreateInstance (so tests may change it in-process).
struct Config {
  int width = 512, height = 512;          // recommended per-eye image size
  float ipd_m = 0.064f;
  float tanHalfFovX = 1.0f, tanHalfFovY = 1.0f;  // symmetric frustum per eye
  double frameRate_hz = 90.0;
  bool realtime = false;                  // pace xrWaitFrame to the wall clock (interactive use)
  std::uint64_t stopAfterFrames = 0;      // frames until STOPPING; 0 = never
  std::uint64_t loseAfterFrames = 0;      // frames until LOSS_PENDING; 0 = never
  std::uint64_t recenterAfterFrames = 0;  // frames until the user re-centres (reference space change events); 0 = never
  bool loseInstance = false;              // loss affects the instance, not only the session
  int restarts = 0;                       // READY again after xrEndSession this many times, then EXITING
  std::filesystem::path outputDir;        // eye PNGs and haptics.jsonl; empty = no output
  std::uint64_t saveEvery = 0;            // save submitted eye images every N frames; 0 = never
  std::filesystem::path scriptPath;       // scripted input (JSON); empty = a still default pose
  bool handTracking = true;               // system reports XR_EXT_hand_tracking support
  double handRate_hz = 0.0;               // > 0: joints are tracked at this rate (a camera), see hand_tracking.cpp
  bool depthLayers = true;                // offer XR_KHR_composition_layer_depth
  bool hapticPcm = false;                 // offer XR_FB_haptic_pcm (a Quest-style controller)
  double hapticPcmCapacity = 0.0;         // > 0: at most this many PCM samples taken per call (a full motor buffer)
  bool hapticEnvelope = false;            // offer XR_FB_haptic_amplitude_envelope
  bool hapticParametric = false;          // offer XR_EXT_haptic_parametric on both controllers
  std::string hapticPcmHands = "left,right";  // controllers that report a PCM rate (others: 0, no PCM)
  std::string profile = "/interaction_profiles/valve/index_controller";  // the "connected" controllers
  Failure failure = Failure::None;
  bool validation = false;                // add VK_LAYER_KHRONOS_validation in xrCreateVulkanInstanceKHR
};

/// Reads XRSIM_CONFIG (JSON, optional) then XRSIM_* variables; throws vt::Error naming the field.
Config loadConfig();

}  // namespace xrsim
