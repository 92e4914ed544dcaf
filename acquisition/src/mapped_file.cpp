#include "mapped_file.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "vt/core/error.hpp"

namespace vt::acq {

MappedFile::MappedFile(const std::filesystem::path& path, std::string_view what) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(what, " '", path.string(), "': file not found");
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail(what, " '", path.string(), "': cannot open");
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    ::close(fd);
    fail(what, " '", path.string(), "': cannot read its size");
  }
  m_size = std::size_t(st.st_size);
  if (m_size > 0) {
    m_data = ::mmap(nullptr, m_size, PROT_READ, MAP_PRIVATE, fd, 0);
    if (m_data == MAP_FAILED) {
      m_data = nullptr;
      ::close(fd);
      fail(what, " '", path.string(), "': cannot map");
    }
    ::madvise(m_data, m_size, MADV_SEQUENTIAL);  // a hint: parsers read front to back
  }
  ::close(fd);  // the mapping keeps the file
}

MappedFile::~MappedFile() {
  if (m_data) ::munmap(m_data, m_size);
}

}  // namespace vt::acq
