#include "vt/core/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <deque>
#include <mutex>
#include <set>

#include "vt/core/error.hpp"
#include "vt/core/file_io.hpp"
#include "vt/core/log.hpp"

namespace vt {
namespace fs = std::filesystem;
namespace {

constexpr std::size_t kBufferBytes = 1 << 16;
constexpr std::chrono::minutes kLeftoverAge{2};  // a live writer's temporary changes more often

// A name no other writer (thread or process) picks: hidden, beside the target, same file system.
fs::path siblingName(const fs::path& target, std::string_view kind) {
  static std::atomic<unsigned> counter{0};
  const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
  return parent / str(".", target.filename().string(), ".", kind, "-", ::getpid(), "-", counter.fetch_add(1));
}

// A process that may still be writing its temporaries (this one, or any live one).
bool processAlive(long pid) {
  if (pid <= 0 || pid == ::getpid()) return true;
  return ::kill(pid_t(pid), 0) == 0 || errno == EPERM;
}

// What siblingName() made: ".TARGET.KIND-PID-N" -> TARGET, KIND and PID (false for anything else).
bool parseSibling(const std::string& name, std::string& target, std::string& kind, long& pid) {
  if (name.size() < 2 || name[0] != '.') return false;
  for (const char* candidate : {"tmp", "staging", "old"}) {
    const std::string marker = str(".", candidate, "-");
    const std::size_t at = name.rfind(marker);
    if (at == std::string::npos || at < 2) continue;
    unsigned long long number = 0, counter = 0;
    int used = 0;
    if (std::sscanf(name.c_str() + at + marker.size(), "%llu-%llu%n", &number, &counter, &used) != 2 ||
        at + marker.size() + std::size_t(used) != name.size())
      continue;
    target = name.substr(1, at - 1), kind = candidate, pid = long(number);
    return true;
  }
  return false;
}

}  // namespace

void removeStaleTemporaries(const fs::path& folder) {
  static std::mutex mutex;
  static std::set<std::string> cleaned;  // once per folder and process: a run writes many files there
  std::error_code ec;
  const fs::path dir = fs::weakly_canonical(folder.empty() ? fs::path(".") : folder, ec);
  if (ec) return;
  {
    const std::lock_guard lock(mutex);
    if (!cleaned.insert(dir.string()).second) return;
  }
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
    std::string target, kind;
    long pid = 0;
    if (!parseSibling(entry.path().filename().string(), target, kind, pid) || processAlive(pid)) continue;
    // A writer in another PID namespace or on another host sharing the folder looks dead here:
    // only what nobody has written for a while is a leftover.
    const auto written = fs::last_write_time(entry.path(), ec);
    if (ec || fs::file_time_type::clock::now() - written < kLeftoverAge) continue;
    std::error_code failed;
    const fs::path leftover = entry.path(), final = dir / target;
    // A run killed between moving the previous folder aside and moving the new one in: put it back.
    if (kind == "old" && fs::symlink_status(final, failed).type() == fs::file_type::not_found &&
        ::rename(leftover.c_str(), final.c_str()) == 0) {
      log::warn("restored '", final.string(), "' from '", leftover.string(), "', left by a run that was killed (pid ", pid,
                ") while replacing it");
      continue;
    }
    if (fs::remove_all(leftover, failed) > 0 && !failed) {
      log::warn("removed '", leftover.string(), "', an unfinished output left by a run that was killed (pid ", pid, ")");
    }
  }
}

OutputFile::OutputFile(fs::path path) : m_path(std::move(path)) {
  struct stat target {};
  if (::stat(m_path.c_str(), &target) != 0) {
    if (errno != ENOENT) throw Error(describeErrno(m_path, "write", errno));
  } else if (S_ISDIR(target.st_mode)) {
    throw Error(describeErrno(m_path, "write", EISDIR));
  } else if (S_ISCHR(target.st_mode)) {
    // A character device (/dev/null, a terminal) is written in place: renaming a file over it
    // would replace the device.
    m_fd = ::open(m_path.c_str(), O_WRONLY | O_CLOEXEC);
    if (m_fd < 0) throw Error(describeErrno(m_path, "write", errno));
    m_buffer.reserve(kBufferBytes);
    return;
  } else if (!S_ISREG(target.st_mode)) {
    const char* kind = S_ISFIFO(target.st_mode) ? "a named pipe (FIFO)" : S_ISSOCK(target.st_mode) ? "a socket"
                       : S_ISBLK(target.st_mode) ? "a block device" : "not a regular file";
    fail("'", m_path.string(), "': cannot write: it is ", kind,
         "; outputs are written whole to regular files: give a file name (or /dev/null to discard it)");
  }
  const fs::path folder = m_path.has_parent_path() ? m_path.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(folder, ec) && fs::symlink_status(folder, ec).type() == fs::file_type::not_found) {
    fail("'", m_path.string(), "': cannot write: the folder '", folder.string(), "' does not exist");
  }
  removeStaleTemporaries(folder);
  m_temporary = siblingName(m_path, "tmp");
  m_fd = ::open(m_temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (m_fd < 0) {
    const int error = errno;
    m_temporary.clear();
    throw Error(describeErrno(m_path, "write", error));
  }
  m_buffer.reserve(kBufferBytes);
}

OutputFile::~OutputFile() { discard(); }

void OutputFile::discard() noexcept {
  if (m_fd >= 0) ::close(m_fd);
  m_fd = -1;
  if (!m_temporary.empty()) ::unlink(m_temporary.c_str());
  m_temporary.clear();
}

void OutputFile::write(const void* data, std::size_t size) {
  if (m_fd < 0) fail("'", m_path.string(), "': write after commit");
  const char* bytes = static_cast<const char*>(data);
  if (m_buffer.size() + size > kBufferBytes) flush();
  if (size >= kBufferBytes) {
    writeAll(bytes, size);  // large blocks skip the buffer
    return;
  }
  m_buffer.insert(m_buffer.end(), bytes, bytes + size);
}

void OutputFile::flush() {
  if (m_fd < 0) fail("'", m_path.string(), "': write after commit");
  writeAll(m_buffer.data(), m_buffer.size());
  m_buffer.clear();
}

void OutputFile::overwrite(std::size_t offset, const void* data, std::size_t size) {
  flush();
  writeAll(static_cast<const char*>(data), size, offset);
}

void OutputFile::writeAll(const char* bytes, std::size_t size, std::size_t offset) {
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = offset == kAppend ? ::write(m_fd, bytes + done, size - done)
                                        : ::pwrite(m_fd, bytes + done, size - done, off_t(offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = n < 0 ? errno : ENOSPC;
      discard();
      if (error == ESPIPE) {
        fail("'", m_path.string(), "': cannot complete this output in place: it is not seekable (its header is "
             "written last); give a regular file");
      }
      throw Error(describeErrno(m_path, "write", error));
    }
    done += std::size_t(n);
  }
}

void OutputFile::commit() {
  if (m_fd < 0) fail("'", m_path.string(), "': committed twice");
  flush();
  const int fd = m_fd;
  m_fd = -1;
  // close() reports delayed write errors (NFS, some full-disk cases): a failure here is a failure.
  if (::close(fd) != 0) {
    const int error = errno;
    discard();
    throw Error(describeErrno(m_path, "write", error));
  }
  if (m_temporary.empty()) return;  // written in place (a device)
  if (::rename(m_temporary.c_str(), m_path.c_str()) != 0) {
    const int error = errno;
    discard();
    throw Error(describeErrno(m_path, "replace", error));
  }
  m_temporary.clear();
}

void writeFileAtomically(const fs::path& path, std::string_view bytes) {
  OutputFile file(path);
  file.write(bytes);
  file.commit();
}

void writeFiles(const std::vector<FileContent>& files, bool replace, std::string_view forceHint) {
  for (const FileContent& file : files) refuseExisting(file.path, replace, forceHint);
  std::deque<OutputFile> outputs;  // OutputFile does not move
  for (const FileContent& file : files) {
    outputs.emplace_back(file.path).write(file.bytes);
    outputs.back().flush();
  }
  for (OutputFile& output : outputs) output.commit();
}

void refuseExisting(const fs::path& path, bool replace, std::string_view forceHint) {
  std::error_code ec;
  if (replace || fs::symlink_status(path, ec).type() == fs::file_type::not_found) return;
  if (fs::is_directory(path, ec) && fs::is_empty(path, ec) && !ec) return;  // nothing to lose
  fail("'", path.string(), "' already exists (use ", forceHint, " to replace it)");
}

StagedFolder::StagedFolder(fs::path finalDir, bool replace, std::string_view forceHint)
    : m_final(fs::absolute(finalDir).lexically_normal()) {
  // "out/" and "." name the folder itself: its siblings live in its parent.
  if (!m_final.has_filename()) m_final = m_final.parent_path();
  std::error_code ec;
  if (m_final.has_parent_path()) {
    fs::create_directories(m_final.parent_path(), ec);
    if (ec) throw Error(describeErrno(m_final.parent_path(), "create the folder", ec.value()));
    removeStaleTemporaries(m_final.parent_path());  // may put back a folder a killed run moved aside
  }
  refuseExisting(m_final, replace, forceHint);
  m_staging = siblingName(m_final, "staging");
  fs::create_directory(m_staging, ec);
  if (ec) {
    const int error = ec.value();
    m_staging.clear();
    throw Error(describeErrno(m_final, "create the folder", error));
  }
}

StagedFolder::~StagedFolder() {
  std::error_code ec;
  if (!m_committed && !m_staging.empty()) fs::remove_all(m_staging, ec);
}

void StagedFolder::commit() {
  std::error_code ec;
  fs::path old;
  if (fs::symlink_status(m_final, ec).type() != fs::file_type::not_found) {
    old = siblingName(m_final, "old");
    if (::rename(m_final.c_str(), old.c_str()) != 0) throw Error(describeErrno(m_final, "replace", errno));
  }
  if (::rename(m_staging.c_str(), m_final.c_str()) != 0) {
    const int error = errno;
    if (!old.empty()) ::rename(old.c_str(), m_final.c_str());  // put the previous folder back
    throw Error(describeErrno(m_final, "move the new folder into place", error));
  }
  m_committed = true;
  if (!old.empty()) fs::remove_all(old, ec);  // a leftover hidden folder costs space, not data
}

}  // namespace vt

namespace vt {

void refuseSharedOutputs(const std::vector<NamedOutput>& outputs) {
  std::vector<std::pair<const NamedOutput*, fs::path>> seen;
  for (const NamedOutput& output : outputs) {
    if (output.path.empty()) continue;
    std::error_code ec;
    struct stat st {};
    if (::stat(output.path.c_str(), &st) == 0 && S_ISCHR(st.st_mode)) continue;  // /dev/null may take them all
    const fs::path resolved = fs::weakly_canonical(fs::absolute(output.path, ec), ec);
    for (const auto& [other, path] : seen) {
      if (path == resolved || fs::equivalent(path, resolved, ec)) {
        fail(other->option, " and ", output.option, " both name '", output.path.string(),
             "': one would overwrite the other; give each output its own file");
      }
    }
    seen.emplace_back(&output, resolved);
  }
}

}  // namespace vt
