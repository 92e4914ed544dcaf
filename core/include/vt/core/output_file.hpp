#pragma once
// Outputs written whole or not at all (docs/RELIABILITY.md): a file is written under a temporary
// name in its own folder, every write and the close are checked, then it is renamed over the
// target; a folder is built under a temporary name beside its place and moved there whole. On
// any failure the previous file or folder is intact and the error names the path. A character
// device (/dev/null) is written in place, never replaced; FIFOs, sockets and block devices are
// refused. Temporaries a killed run left are removed (or a moved-aside folder put back) the next
// time an output goes to their folder. Setup threads.
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace vt {

/// One output file, committed by rename (written in place when it is a character device). Not
/// copyable; the destructor removes an uncommitted temporary.
class OutputFile {
 public:
  /// Opens a temporary file beside `path` (whose folder must exist); throws vt::Error naming it
  /// (a folder, a FIFO or another special file there is refused before anything is written).
  explicit OutputFile(std::filesystem::path path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  /// Appends bytes (buffered); throws vt::Error naming the path (ENOSPC says the disk is full).
  void write(const void* data, std::size_t size);
  void write(std::string_view text) { write(text.data(), text.size()); }
  /// Rewrites bytes already written at `offset` (a header whose sizes are known at the end).
  void overwrite(std::size_t offset, const void* data, std::size_t size);
  /// Writes the buffered bytes now (a full disk shows before any file of a set is renamed).
  void flush();
  /// Flushes, closes (checked) and renames over the target; throws vt::Error naming the path.
  void commit();
  const std::filesystem::path& path() const { return m_path; }

 private:
  void writeAll(const char* bytes, std::size_t size, std::size_t offset = kAppend);
  static constexpr std::size_t kAppend = ~std::size_t(0);
  void discard() noexcept;

  std::filesystem::path m_path, m_temporary;
  int m_fd = -1;
  std::vector<char> m_buffer;
};

/// Writes `bytes` to `path` through an OutputFile.
void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes);

/// One file of a set that belongs together (a glTF, its .bin and its images).
struct FileContent {
  std::filesystem::path path;
  std::string bytes;
};
/// Writes a set of files: refused (naming the first that exists and `forceHint`) unless `replace`;
/// every file is written and flushed before the first is renamed, so a full disk leaves them all
/// as they were. Throws vt::Error naming the path.
void writeFiles(const std::vector<FileContent>& files, bool replace, std::string_view forceHint = "--force");

/// A folder built under a temporary name beside `finalDir` and moved into place by commit().
/// An existing non-empty `finalDir` is refused (the message suggests `forceHint`) unless `replace`; when
/// replaced, the old folder stays until the new one is in place.
class StagedFolder {
 public:
  StagedFolder(std::filesystem::path finalDir, bool replace, std::string_view forceHint = "--force");
  ~StagedFolder();
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;

  /// Where to write the folder's files until commit().
  const std::filesystem::path& dir() const { return m_staging; }
  /// Moves the staged folder to its final name (replacing the old one); throws vt::Error.
  void commit();

 private:
  std::filesystem::path m_final, m_staging;
  bool m_committed = false;
};

/// Removes the temporaries (".NAME.tmp-PID-N", ".NAME.staging-PID-N") that runs which were killed
/// left in `folder`, and puts back a folder a killed run had moved aside (".NAME.old-PID-N") when
/// its place is empty; each one logged. Once per folder and process; those of live processes,
/// and any written in the last 2 minutes (a writer this process cannot see), are kept.
void removeStaleTemporaries(const std::filesystem::path& folder);

/// One output of a command, named as the user gave it ("--record-csv", its path).
struct NamedOutput {
  std::string option;
  std::filesystem::path path;
};
/// Refuses (vt::Error naming both options and the path) when two non-empty outputs are the same
/// file, before anything is written; character devices (/dev/null) may be shared.
void refuseSharedOutputs(const std::vector<NamedOutput>& outputs);

/// Refuses (vt::Error naming it and `forceHint`) when `path` exists (an empty folder does not
/// count), unless `replace`.
void refuseExisting(const std::filesystem::path& path, bool replace, std::string_view forceHint = "--force");

}  // namespace vt
