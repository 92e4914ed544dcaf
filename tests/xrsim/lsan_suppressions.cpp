// LeakSanitizer suppressions for the tests that go through the OpenXR loader and Vulkan
// (used by vt_xrsim_tests and vt_xr_tests). Both leaks are outside V-Touching, measured on
// Debian 12: libopenxr_loader 1.0.20 keeps ~1.3 KB of instance bookkeeping after
// xrDestroyInstance, and Mesa 22.3 lavapipe leaks a 128-byte block (plus what it points to)
// per vkCreateInstance. lavapipe is pinned in memory so that its frames still have a module
// name when LeakSanitizer reports at exit (the Vulkan loader unloads it otherwise).
#if defined(__SANITIZE_ADDRESS__)
#include <dlfcn.h>

extern "C" const char* __lsan_default_suppressions();
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libopenxr_loader.so\n"
         "leak:libvulkan_lvp.so\n";
}

namespace {
const bool kLavapipePinned = dlopen("libvulkan_lvp.so", RTLD_NOW | RTLD_NODELETE) != nullptr;
}  // namespace
#endif
