#include "io/file_bytes.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fcntl.h>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>

namespace igi {

bool inside_folder(const std::string& root, const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::path target = fs::weakly_canonical(path, error);
  if (root.empty() || error) return false;
  const fs::path base(root);
  return std::mismatch(base.begin(), base.end(), target.begin(), target.end()).first == base.end();
}

namespace {

// A file descriptor closed on every path out.
struct Fd {
  int fd;
  ~Fd() { if (fd >= 0) ::close(fd); }
};

}  // namespace

std::optional<std::vector<uint8_t>> read_file_bytes(const std::string& path) {
  const Fd in{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
  struct stat st;
  if (in.fd < 0 || ::fstat(in.fd, &st) != 0 || !S_ISREG(st.st_mode)) return std::nullopt;
  std::vector<uint8_t> bytes(size_t(st.st_size));
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::read(in.fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return std::nullopt;  // an error, or the file shrank while we read it
    done += size_t(n);
  }
  return bytes;
}

void write_new_file(const std::string& path, const void* data, size_t size, unsigned mode, Umask umask) {
  const Fd out{::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, mode)};
  if (out.fd < 0) throw std::runtime_error(path + ": cannot create (" + std::strerror(errno) + ")");
  bool ok = umask == Umask::applies || ::fchmod(out.fd, mode) == 0;
  const auto* bytes = static_cast<const uint8_t*>(data);
  for (size_t done = 0; ok && done < size;) {
    const ssize_t n = ::write(out.fd, bytes + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    ok = n > 0;
    if (ok) done += size_t(n);
  }
  if (!ok) throw std::runtime_error(path + ": cannot write (" + std::strerror(errno) + ")");
}

}  // namespace igi
