#include "rondo/core/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "rondo/core/utf8.h"

namespace rondo {
namespace {

Error os_error(const std::filesystem::path& file, const char* doing, int err) {
  return Error::io(printable_path(file) + ": " + doing + ": " + std::strerror(err));
}

// Closes the descriptor and removes the temporary file unless released.
class TempFile {
 public:
  TempFile(int fd, std::filesystem::path path) : fd_(fd), path_(std::move(path)) {}
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  ~TempFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!path_.empty()) ::unlink(path_.c_str());
  }
  int fd() const { return fd_; }
  const std::filesystem::path& path() const { return path_; }
  int close() {
    const int r = ::close(fd_);
    fd_ = -1;
    return r;
  }
  void keep() { path_.clear(); }

 private:
  int fd_;
  std::filesystem::path path_;
};

}  // namespace

Status write_file_atomically(const std::filesystem::path& file, std::string_view bytes) {
  const std::filesystem::path folder = file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
  std::string pattern = (folder / ("." + file.filename().string() + ".tmp-XXXXXX")).string();
  const int fd = ::mkstemp(pattern.data());
  if (fd < 0) return os_error(file, "cannot create a temporary file beside it", errno);
  TempFile temp(fd, pattern);
  // mkstemp makes the file 0600; a written file gets the usual mode (0666 less the umask).
  const mode_t mask = ::umask(0);
  ::umask(mask);
  if (::fchmod(temp.fd(), 0666 & ~mask) != 0) return os_error(file, "cannot set the mode", errno);
  for (std::size_t done = 0; done < bytes.size();) {
    const ssize_t n = ::write(temp.fd(), bytes.data() + done, bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return os_error(file, "write failed", errno);
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(temp.fd()) != 0) return os_error(file, "sync failed", errno);
  if (temp.close() != 0) return os_error(file, "write failed", errno);
  if (::rename(temp.path().c_str(), file.c_str()) != 0) return os_error(file, "cannot replace", errno);
  temp.keep();
  // The rename is durable once the folder is synced; a folder that cannot be opened (or synced,
  // on some file systems) does not undo a write that has already happened.
  if (const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dir >= 0) {
    ::fsync(dir);
    ::close(dir);
  }
  return {};
}

}  // namespace rondo
