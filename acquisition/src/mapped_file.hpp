#pragma once
// A whole input file mapped read-only: logs of a million rows are parsed where the page
// cache holds them, with no copy into a string first.
#include <filesystem>
#include <string_view>

namespace vt::acq {

class MappedFile {
 public:
  /// Maps `path`; errors name `what` and the path ("robot log 'x.csv': file not found").
  MappedFile(const std::filesystem::path& path, std::string_view what);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  /// The file's bytes (empty for an empty file); valid while this object lives.
  std::string_view bytes() const noexcept { return {static_cast<const char*>(m_data), m_size}; }

 private:
  void* m_data = nullptr;
  std::size_t m_size = 0;
};

}  // namespace vt::acq
