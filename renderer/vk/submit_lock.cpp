#include "renderer/vk/submit_lock.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

namespace gib {
namespace {

// The lock file's descriptor, opened on first use and kept for the process's life (-1: no lock).
int lock_fd() {
  static const int fd = [] {
    const char* path = std::getenv("GIB_GPU_SUBMIT_LOCK");
    return path && *path ? SubmitGuard::open_lock(path) : -1;
  }();
  return fd;
}

}  // namespace

int SubmitGuard::open_lock(const char* path) {
  int f = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (f < 0)
    throw std::runtime_error(
        fmt::format("GIB_GPU_SUBMIT_LOCK: cannot open the lock file '{}': {}", path, std::strerror(errno)));
  return f;
}

SubmitGuard::SubmitGuard() : SubmitGuard(lock_fd()) {}

SubmitGuard::SubmitGuard(int fd) : fd_(fd) {
  if (fd_ < 0) return;
  while (flock(fd_, LOCK_EX) != 0) {
    if (errno == EINTR) continue;
    throw std::runtime_error(fmt::format("GIB_GPU_SUBMIT_LOCK: flock failed: {}", std::strerror(errno)));
  }
}

SubmitGuard::~SubmitGuard() {
  if (fd_ >= 0) flock(fd_, LOCK_UN);
}

}  // namespace gib
