#pragma once
// One binding function per area of the module (python/src/*.cpp).
#include <pybind11/pybind11.h>

namespace vt::python {

/// Images, vibration maps, datasets, acquisition, statistics, sampling along a path.
void bindMaps(pybind11::module_& m);
/// encode / decode with the tactile stream codec.
void bindCodec(pybind11::module_& m);
/// Haptic clips: recordings, HJIF / AHAP / .haptic / WAV, conversion losses.
void bindFiles(pybind11::module_& m);

}  // namespace vt::python
