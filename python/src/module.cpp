// `import vtouching`: the native part (_vtouching). Maps, acquisition, statistics, path sampling
// with the haptic loop's renderer, the tactile codec and the haptic files, over numpy arrays.
// vt::Error becomes vtouching.Error carrying the message the CLI prints. Python's thread only.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "vt/core/error.hpp"

namespace py = pybind11;

PYBIND11_MODULE(_vtouching, m) {
  m.doc() = "V-Touching: vibration maps, acquisition, path sampling, the tactile codec and haptic files";
  static py::exception<vt::Error> error(m, "Error", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const vt::Error& e) {
      error(e.what());
    } catch (const std::filesystem::filesystem_error& e) {
      // As the CLI words it (app/main.cpp).
      error(("'" + e.path1().string() + "': " + e.code().message()).c_str());
    }
  });
  vt::python::bindMaps(m);
  vt::python::bindCodec(m);
  vt::python::bindFiles(m);
}
