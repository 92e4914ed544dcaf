#include "vt/core/output_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <deque>

#include "vt/core/error.hpp"
#include "vt/core/file_io.hpp"

namespace vt {
namespace fs = std::filesystem;
namespace {

constexpr std::size_t kBufferBytes = 1 << 16;

// A name no other writer (thread or process) picks: hidden, beside the target, same file system.
fs::path siblingName(const fs::path& target, std::string_view kind) {
  static std::atomic<unsigned> counter{0};
  const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
  return parent / str(".", target.filename().string(), ".", kind, "-", ::getpid(), "-", counter.fetch_add(1));
}

}  // namespace

OutputFile::OutputFile(fs::path path) : m_path(std::move(path)), m_temporary(siblingName(m_path, "tmp")) {
  m_fd = ::open(m_temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (m_fd < 0) throw Error(describeErrno(m_path, "write", errno));
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
  refuseExisting(m_final, replace, forceHint);
  std::error_code ec;
  if (m_final.has_parent_path()) {
    fs::create_directories(m_final.parent_path(), ec);
    if (ec) throw Error(describeErrno(m_final.parent_path(), "create the folder", ec.value()));
  }
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
