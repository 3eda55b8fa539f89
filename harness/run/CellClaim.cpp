#include "harness/run/CellClaim.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>
#include <utility>

#include "core/Errors.h"

namespace cdb {

std::optional<CellClaim> CellClaim::take(const std::filesystem::path& runDir,
                                         const std::string& cellKey) {
  const std::filesystem::path dir = runDir / "claims";
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw RunError(dir.string() + ": cannot be created (" + ec.message() + ")");
  std::filesystem::path file = dir / (cellKey + ".lock");
  const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) throw RunError(file.string() + ": cannot be opened (" + std::strerror(errno) + ")");
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(fd);
    if (error == EWOULDBLOCK) return std::nullopt;
    throw RunError(file.string() + ": cannot be locked (" + std::strerror(error) + ")");
  }
  return CellClaim(std::move(file), fd);
}

CellClaim::CellClaim(CellClaim&& other) noexcept
    : file_(std::move(other.file_)), fd_(std::exchange(other.fd_, -1)) {}

CellClaim& CellClaim::operator=(CellClaim&& other) noexcept {
  if (this != &other) {
    release(false);
    file_ = std::move(other.file_);
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

void CellClaim::release(bool removeFile) noexcept {
  if (fd_ < 0) return;
  if (removeFile) {
    std::error_code ignored;  // a file already gone claims nothing either
    std::filesystem::remove(file_, ignored);
  }
  ::close(fd_);  // (closing the only descriptor unlocks)
  fd_ = -1;
}

}  // namespace cdb
