// Haptic clips as dicts of numpy arrays: {"sample_rate_hz", "duration_s", "description",
// "channels": [{"actuator", "envelope" (N, 3) t_s/amplitude/frequency_hz, "pcm" float32}]}.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "vt/core/error.hpp"
#include "vt/haptics/files/haptic_formats.hpp"

namespace py = pybind11;

namespace vt::python {
namespace {

namespace files = haptics::files;

py::dict clipToPython(const files::HapticClip& clip) {
  py::list channels;
  for (const files::ClipChannel& c : clip.channels) {
    py::array_t<double> envelope({py::ssize_t(c.envelope.size()), py::ssize_t(3)});
    auto e = envelope.mutable_unchecked<2>();
    for (std::size_t i = 0; i < c.envelope.size(); ++i) {
      const auto row = py::ssize_t(i);
      e(row, 0) = c.envelope[i].t_s, e(row, 1) = c.envelope[i].amplitude, e(row, 2) = c.envelope[i].frequency_hz;
    }
    py::dict channel;
    channel["actuator"] = std::string(haptics::actuatorName(c.actuator));
    channel["envelope"] = envelope;
    channel["pcm"] = py::array_t<float>(py::ssize_t(c.pcm.size()), c.pcm.data());
    channels.append(channel);
  }
  py::dict d;
  d["sample_rate_hz"] = clip.sampleRate_hz;
  d["duration_s"] = clip.duration_s;
  d["description"] = clip.description;
  d["channels"] = channels;
  return d;
}

files::HapticClip clipFromPython(const py::dict& d) {
  files::HapticClip clip;
  clip.sampleRate_hz = d.contains("sample_rate_hz") ? d["sample_rate_hz"].cast<std::uint32_t>() : 0;
  clip.duration_s = d["duration_s"].cast<double>();
  clip.description = d.contains("description") ? d["description"].cast<std::string>() : "";
  if (!(clip.duration_s >= 0.0 && clip.duration_s <= files::kMaxRecording_s))
    fail("clip: duration_s ", clip.duration_s, " outside 0..", files::kMaxRecording_s);
  for (const py::handle item : d["channels"]) {
    const py::dict c = item.cast<py::dict>();
    files::ClipChannel channel;
    channel.actuator = files::parseActuator(c["actuator"].cast<std::string>(), "clip channel");
    if (c.contains("envelope")) {
      const auto e = c["envelope"].cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
      if (e.size() > 0 && (e.ndim() != 2 || e.shape(1) != 3)) fail("clip channel: envelope must be an (N, 3) array of t_s, amplitude, frequency_hz");
      for (py::ssize_t i = 0; e.size() > 0 && i < e.shape(0); ++i)
        channel.envelope.push_back({e.at(i, 0), float(e.at(i, 1)), float(e.at(i, 2))});
    }
    if (c.contains("pcm")) {
      const auto p = c["pcm"].cast<py::array_t<float, py::array::c_style | py::array::forcecast>>();
      channel.pcm.assign(p.data(), p.data() + p.size());
    }
    clip.channels.push_back(std::move(channel));
  }
  return clip;
}

}  // namespace

void bindFiles(py::module_& m) {
  m.def("load_recording",
        [](const std::optional<std::filesystem::path>& csv, const std::optional<std::filesystem::path>& wav) {
          return clipToPython(files::loadRecording(csv.value_or(""), wav.value_or("")));
        },
        py::arg("csv") = py::none(), py::arg("wav") = py::none(),
        "An actuator recording (--record-csv and/or --record-wav) as a clip dict.");
  m.def("load_haptic_file",
        [](const std::filesystem::path& path, const std::string& actuator) {
          return clipToPython(files::loadHapticFile(path, files::parseActuator(actuator, "load_haptic_file: actuator")));
        },
        py::arg("path"), py::arg("actuator") = "index", "Reads .hjif, .ahap, .haptic or .wav (what `vtouching play` reads).");
  m.def("save_haptic_file",
        [](const py::dict& clip, const std::filesystem::path& path, bool force) {
          std::vector<std::string> out;
          for (const auto& p : files::saveHapticFile(clipFromPython(clip), path, force)) out.push_back(p.string());
          return out;
        },
        py::arg("clip"), py::arg("path"), py::arg("force") = false,
        "Writes a clip as .hjif, .ahap, .haptic or .wav (split and per-actuator as `vtouching convert`); returns the files.");
  m.def("conversion_losses",
        [](const py::dict& clip, const std::string& extension) {
          return files::conversionLosses(clipFromPython(clip), files::hapticFormat("clip" + extension));
        },
        py::arg("clip"), py::arg("extension"), "What writing the clip as EXTENSION ('.ahap', ...) loses, one sentence each.");
}

}  // namespace vt::python
