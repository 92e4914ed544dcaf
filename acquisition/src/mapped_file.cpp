#include "mapped_file.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <limits>

#include "vt/core/error.hpp"
#include "vt/core/file_io.hpp"

namespace vt::acq {

MappedFile::MappedFile(const std::filesystem::path& path, std::string_view what) {
  // A folder, a symlink loop, a missing file or no permission: each named, with the reason.
  checkInputFile(path, what, std::numeric_limits<std::uintmax_t>::max());
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw Error(str(what, " ", describeErrno(path, "read", errno)));
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int error = errno;
    ::close(fd);
    throw Error(str(what, " ", describeErrno(path, "read its size", error)));
  }
  m_size = std::size_t(st.st_size);
  if (m_size > 0) {
    m_data = ::mmap(nullptr, m_size, PROT_READ, MAP_PRIVATE, fd, 0);
    if (m_data == MAP_FAILED) {
      const int error = errno;
      m_data = nullptr;
      ::close(fd);
      throw Error(str(what, " ", describeErrno(path, "map", error)));
    }
    ::madvise(m_data, m_size, MADV_SEQUENTIAL);  // a hint: parsers read front to back
  }
  ::close(fd);  // the mapping keeps the file
}

MappedFile::~MappedFile() {
  if (m_data) ::munmap(m_data, m_size);
}

}  // namespace vt::acq
