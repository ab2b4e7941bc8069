#include "core/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace fluidem {

std::optional<std::string> input_file_problem(const std::string& path, bool allow_pipe) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    const int err = errno;
    struct stat link {};
    if (err == ENOENT && ::lstat(path.c_str(), &link) == 0 && S_ISLNK(link.st_mode))
      return "is a symbolic link to a file that does not exist";
    if (err == ENOENT) return "does not exist";
    return "cannot be opened: " + std::string(std::strerror(err));
  }
  if (S_ISDIR(st.st_mode)) return "is a directory, not a file";
  if (S_ISFIFO(st.st_mode)) {
    if (allow_pipe) return std::nullopt;
    return "is a named pipe, not a regular file";
  }
  if (S_ISCHR(st.st_mode)) return "is a character device, not a regular file";
  if (S_ISBLK(st.st_mode)) return "is a block device, not a regular file";
  if (S_ISSOCK(st.st_mode)) return "is a socket, not a regular file";
  if (!S_ISREG(st.st_mode)) return "is not a regular file";
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return "cannot be opened: " + std::string(std::strerror(errno));
  ::close(fd);
  return std::nullopt;
}

std::string read_failure(int errno_value) {
  return "cannot be read: " +
         std::string(errno_value != 0 ? std::strerror(errno_value) : "read error");
}

} // namespace fluidem
