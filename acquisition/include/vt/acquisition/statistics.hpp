#pragma once
// The paper's Table I: per object, on taxel values before normalisation. Any thread.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace vt::acq {

/// V_scale = max - min, V_mean, V_std (population) of a set of values.
struct TaxelStats {
  double scale = 0, mean = 0, std = 0, min = 0, max = 0;
  std::size_t count = 0;
};

/// Statistics of the values; all zero for an empty set.
TaxelStats computeStats(std::span<const double> values) noexcept;

/// Where an object's statistics came from.
enum class StatsSource {
  Taxels,         // taxel values in g (from NAME_map.json written by `vtouching acquire`)
  NormalisedPng,  // pixel values of the 8/16-bit min-max normalised NAME_acc.png (unitless, area-weighted)
};

/// One row of the table.
struct ObjectStats {
  std::string name;
  StatsSource source = StatsSource::Taxels;
  TaxelStats stats;
  std::optional<double> noise_g;         // the accelerometer's noise floor, when NAME_map.json records it
  std::optional<TaxelStats> corrected;   // noise-corrected statistics, when NAME_map.json records them
};

/// Statistics of every object folder NAME/ (holding NAME_acc.png) in a dataset directory,
/// sorted by name. Throws vt::Error naming the folder/file when none is found or one is bad.
std::vector<ObjectStats> datasetStats(const std::filesystem::path& dir);

/// The table as CSV text (name,source,v_scale,v_mean,v_std,count,noise_g,v_scale_corrected,
/// v_mean_corrected,v_std_corrected; the last four empty when unknown).
std::string statsCsv(std::span<const ObjectStats> rows);
/// The table as JSON text.
std::string statsJson(std::span<const ObjectStats> rows);
/// Human-readable table, Table-I style.
std::string statsTable(std::span<const ObjectStats> rows);

}  // namespace vt::acq
