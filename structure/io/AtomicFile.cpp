#include "structure/io/AtomicFile.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>

namespace fsi::structure {
namespace {

namespace fs = std::filesystem;

// The data must be on disk before the rename makes it the current content, or a machine crash could leave an
// empty file under the final name.
void syncToDisk(const fs::path& path, const char* who) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0 || ::fsync(fd) != 0) {
    const int err = errno;
    if (fd >= 0) ::close(fd);
    throw std::runtime_error(fmt::format("{}: cannot sync '{}': {}", who, path.string(), std::strerror(err)));
  }
  if (::close(fd) != 0)
    throw std::runtime_error(
        fmt::format("{}: cannot close '{}': {}", who, path.string(), std::strerror(errno)));
}

// The rename is durable once the directory entry is on disk. Best effort: some file systems refuse to sync
// a directory, and the file itself is complete either way.
void syncDirectory(const fs::path& dir) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;
  (void)::fsync(fd);
  ::close(fd);
}

}  // namespace

void replaceFileAtomically(const fs::path& file, const char* who,
                           const std::function<void(const fs::path& tmp)>& write) {
  fs::path tmp = file;
  tmp += ".tmp";
  try {
    write(tmp);
    syncToDisk(tmp, who);
    std::error_code ec;
    fs::rename(tmp, file, ec);
    if (ec) {
      throw std::runtime_error(
          fmt::format("{}: cannot rename '{}' to '{}': {}", who, tmp.string(), file.string(), ec.message()));
    }
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
  syncDirectory(file.parent_path());
}

}  // namespace fsi::structure
