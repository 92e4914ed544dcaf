#include "vt/core/file_io.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "vt/core/error.hpp"

namespace vt {
namespace fs = std::filesystem;

std::string describeErrno(const fs::path& path, std::string_view action, int error) {
  const char* why = nullptr;
  switch (error) {
    case ENOSPC: why = "no space left on the disk"; break;
    case EDQUOT: why = "disk quota exceeded"; break;
    case EACCES:
    case EPERM: why = "permission denied"; break;
    case ELOOP: why = "too many levels of symbolic links (a symlink loop?)"; break;
    case EISDIR: why = "is a folder, expected a file"; break;
    case ENOTDIR: why = "a part of the path is not a folder"; break;
    case EEXIST: why = "something of that name is in the way"; break;
    case ENOENT: why = "file not found"; break;
    case EROFS: why = "read-only file system"; break;
    case ENAMETOOLONG: why = "name too long"; break;
    case ENOMEM: why = "out of memory"; break;
    default: why = std::strerror(error);
  }
  return str("'", path.string(), "': cannot ", action, ": ", why);
}

std::uintmax_t checkInputFile(const fs::path& path, std::string_view what, std::uintmax_t maxBytes) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec && ec.value() != ENOENT) throw Error(str(what, " ", describeErrno(path, "read", ec.value())));
  switch (status.type()) {
    case fs::file_type::regular: break;
    case fs::file_type::not_found:
      if (fs::is_symlink(fs::symlink_status(path, ec))) fail(what, " '", path.string(), "': broken symbolic link");
      fail(what, " '", path.string(), "': file not found");
    case fs::file_type::directory: fail(what, " '", path.string(), "': is a folder, expected a file");
    default: fail(what, " '", path.string(), "': not a regular file");
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw Error(str(what, " ", describeErrno(path, "read", ec.value())));
  if (size > maxBytes) {
    fail(what, " '", path.string(), "': ", size, " bytes is over the limit of ", maxBytes,
         " bytes (docs/RELIABILITY.md)");
  }
  return size;
}

namespace {

template <class Bytes>
Bytes readWhole(const fs::path& path, std::string_view what, std::uintmax_t maxBytes) {
  const std::uintmax_t size = checkInputFile(path, what, maxBytes);
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw Error(str(what, " ", describeErrno(path, "read", errno)));
  Bytes bytes(std::size_t(size), 0);
  std::size_t done = 0;
  int error = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::read(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) error = errno;
    if (n <= 0) break;  // shorter than stat said (truncated meanwhile): keep what is there
    done += std::size_t(n);
  }
  ::close(fd);
  if (error) throw Error(str(what, " ", describeErrno(path, "read", error)));
  bytes.resize(done);
  return bytes;
}

}  // namespace

std::string readInputFile(const fs::path& path, std::string_view what, std::uintmax_t maxBytes) {
  return readWhole<std::string>(path, what, maxBytes);
}

std::vector<unsigned char> readInputBytes(const fs::path& path, std::string_view what, std::uintmax_t maxBytes) {
  return readWhole<std::vector<unsigned char>>(path, what, maxBytes);
}

}  // namespace vt
