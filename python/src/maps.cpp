// Images, maps, datasets, acquisition and sampling along a path (python/vtouching docs).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>

#include "bindings.hpp"
#include "vt/acquisition/pipeline.hpp"
#include "vt/acquisition/statistics.hpp"
#include "vt/core/error.hpp"
#include "vt/haptics/actuator_frame.hpp"
#include "vt/haptics/tactile_model.hpp"
#include "vt/haptics/vibration_map.hpp"
#include "vt/scene/image.hpp"

namespace py = pybind11;

namespace vt::python {
namespace {

template <class Sample>
py::array_t<Sample> toNumpy(const Image<Sample>& image) {
  std::vector<py::ssize_t> shape{image.height, image.width};
  if (image.channels > 1) shape.push_back(image.channels);
  py::array_t<Sample> out(shape);
  std::copy(image.pixels.begin(), image.pixels.end(), out.mutable_data());
  return out;
}

// A (H, W) float array as a VibrationMap, checked as the loaders check files.
haptics::VibrationMap mapFromNumpy(const py::array_t<float, py::array::c_style | py::array::forcecast>& values) {
  if (values.ndim() != 2) fail("map: expected a 2-D array (height, width), got ", values.ndim(), " dimensions");
  return haptics::vibrationMapFromFloats(int(values.shape(1)), int(values.shape(0)),
                                         std::span<const float>(values.data(), std::size_t(values.size())), "map array");
}

std::vector<glm::vec2> pathFromNumpy(const py::array_t<float, py::array::c_style | py::array::forcecast>& uv) {
  if (uv.ndim() != 2 || uv.shape(1) != 2) fail("path: expected an (N, 2) array of (u, v)");
  std::vector<glm::vec2> out(std::size_t(uv.shape(0)));
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = {uv.data()[2 * i], uv.data()[2 * i + 1]};
  return out;
}

py::dict statsDict(const acq::TaxelStats& s) {
  py::dict d;
  d["scale"] = s.scale, d["mean"] = s.mean, d["std"] = s.std, d["min"] = s.min, d["max"] = s.max, d["count"] = s.count;
  return d;
}

}  // namespace

void bindMaps(py::module_& m) {
  m.def("load_image", [](const std::filesystem::path& path, int channels) { return toNumpy(loadImage8(path, channels)); },
        py::arg("path"), py::arg("channels") = 4, "An 8-bit image (PNG/JPEG) as uint8 (H, W[, C]), top row first.");
  m.def("load_map", [](const std::filesystem::path& path) { return toNumpy(haptics::loadVibrationMapPng(path).intensity()); },
        py::arg("path"), "A vibration map PNG (NAME_acc.png) as float32 (H, W) in 0..1, as the haptic loop loads it.");
  m.def("sample_path",
        [](const py::array_t<float, py::array::c_style | py::array::forcecast>& map,
           const py::array_t<float, py::array::c_style | py::array::forcecast>& uv, bool wrap) {
          const haptics::VibrationMap vibration = mapFromNumpy(map);
          const auto path = pathFromNumpy(uv);
          py::array_t<float> out(py::ssize_t(path.size()));
          for (std::size_t i = 0; i < path.size(); ++i) out.mutable_data()[i] = vibration.sample(path[i], wrap);
          return out;
        },
        py::arg("map"), py::arg("uv"), py::arg("wrap") = false,
        "The map's value at each (u, v) of an (N, 2) path: VibrationMap::sample, the haptic loop's lookup.");
  m.def("render_path",
        [](const py::array_t<float, py::array::c_style | py::array::forcecast>& map,
           const py::array_t<float, py::array::c_style | py::array::forcecast>& uv, float depth_m, float gain,
           const std::string& model, float sampleRate_hz, int tickRate_hz) {
          if (model != "paper" && model != "texture") fail("render_path: model '", model, "' is not paper or texture");
          if (!(tickRate_hz >= 250 && tickRate_hz <= 4000)) fail("render_path: tick rate ", tickRate_hz, " Hz outside 250..4000");
          const auto block = std::size_t(sampleRate_hz / float(tickRate_hz));
          if (block < 1 || block > std::size_t(haptics::kMaxBlockSamples))
            fail("render_path: ", sampleRate_hz, " Hz at ", tickRate_hz, " ticks/s is not 1..", haptics::kMaxBlockSamples, " samples a tick");
          const haptics::VibrationMap vibration = mapFromNumpy(map);
          const auto path = pathFromNumpy(uv);
          haptics::TactileModelConfig config;
          config.model = model == "paper" ? haptics::TactileModelKind::PaperIntensity : haptics::TactileModelKind::TextureWaveform;
          config.sampleRate_hz = sampleRate_hz;
          haptics::TactileModel tactile(config);
          py::array_t<float> intensity(py::ssize_t(path.size())), frequency(py::ssize_t(path.size()));
          py::array_t<float> waveform(py::ssize_t(path.size() * block));
          for (std::size_t i = 0; i < path.size(); ++i) {
            haptics::ContactInput input;
            input.inContact = true;
            input.map = &vibration;
            input.uvStart = path[i > 0 ? i - 1 : 0];
            input.uvEnd = path[i];
            input.depth_m = depth_m;
            input.gain = gain;
            const auto out = tactile.render(input, std::span<float>(waveform.mutable_data() + i * block, block));
            intensity.mutable_data()[i] = out.intensity;
            frequency.mutable_data()[i] = out.frequency_hz;
          }
          return py::make_tuple(intensity, frequency, waveform);
        },
        py::arg("map"), py::arg("uv"), py::arg("depth_m") = 0.0f, py::arg("gain") = 0.5f, py::arg("model") = "paper",
        py::arg("sample_rate_hz") = 8000.0f, py::arg("tick_rate_hz") = 1000,
        "One haptic tick per (u, v) of the path through the loop's TactileModel: (intensity, frequency_hz, waveform).");
  m.def("stats",
        [](const std::filesystem::path& dir) {
          py::list rows;
          for (const acq::ObjectStats& row : acq::datasetStats(dir)) {
            py::dict d = statsDict(row.stats);
            d["name"] = row.name;
            d["source"] = row.source == acq::StatsSource::Taxels ? "taxels" : "normalised-png";
            rows.append(d);
          }
          return rows;
        },
        py::arg("dataset_dir"), "Table I of a dataset folder (what `vtouching stats` prints), one dict per object.");
  m.def("acquire",
        [](const std::filesystem::path& scanDir, const std::optional<std::filesystem::path>& out, int jobs, bool force) {
          acq::AcquireOptions options;
          options.jobs = jobs;
          const acq::AcquireResult result = [&] {
            py::gil_scoped_release release;
            return acq::acquire(acq::loadScan(scanDir), options);
          }();
          if (out) acq::writeDataset(result, *out, true, force);
          py::dict d;
          d["map"] = toNumpy(acq::normaliseMap(result.map));
          d["map_g"] = toNumpy(result.map.value_g);
          d["coverage"] = toNumpy(result.map.coverage);
          d["photo"] = toNumpy(result.photo);
          d["stats"] = statsDict(result.stats);
          d["mm_per_pixel"] = py::make_tuple(result.mmPerPixel[0], result.mmPerPixel[1]);
          d["physical_size_m"] = py::make_tuple(result.physicalSize_m[0], result.physicalSize_m[1]);
          d["lines"] = result.lines.size();
          return d;
        },
        py::arg("scan_dir"), py::arg("out") = py::none(), py::arg("jobs") = 0, py::arg("force") = false,
        "`vtouching acquire SCAN_DIR [--out DIR]`: the map (normalised and in g), coverage, photo and statistics.");
}

}  // namespace vt::python
