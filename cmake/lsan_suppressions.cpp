// LeakSanitizer support, linked into every executable of an ASan build (vt_target_settings):
// the tests and the app go through the OpenXR loader and Vulkan.
// - Two leaks are outside V-Touching, measured on Debian 12: libopenxr_loader 1.0.20 keeps
//   ~1.3 KB of instance bookkeeping after xrDestroyInstance, and Mesa 22.3 lavapipe leaks a
//   128-byte block (plus what it points to) per vkCreateInstance. Suppressed by module.
// - The loaders dlclose() layers and drivers (validation layer, lavapipe) at instance
//   destruction; memory those modules still reference then looks leaked, and their frames lose
//   their module name so no suppression matches. dlclose is a no-op in these builds, so only
//   real leaks are reported.
#ifdef VT_SANITIZER_ADDRESS
extern "C" const char* __lsan_default_suppressions();
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libopenxr_loader.so\n"
         "leak:libvulkan_lvp.so\n";
}

extern "C" int dlclose(void*) { return 0; }
#endif
