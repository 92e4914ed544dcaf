// LeakSanitizer reports memory that a Vulkan layer or driver (validation layer, lavapipe) still
// references as leaked once the loader dlclose()s that module at vkDestroyInstance: the roots
// vanish with the unmapped module. In sanitizer builds this test binary keeps modules loaded
// (its dlclose interposes the C library's), so only real leaks are reported.
#if defined(__SANITIZE_ADDRESS__)
extern "C" int dlclose(void*) { return 0; }
#endif
