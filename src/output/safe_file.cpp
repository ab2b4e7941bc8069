#include "output/safe_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <vector>

namespace fluidem::safe_file {

namespace {

[[noreturn]] void fail(const std::string& what, const std::string& path, int err) {
  throw OutputError(
      "cannot " + what + " '" + path + "': " + std::strerror(err) +
      (err == ELOOP ? " (it is a symbolic link; fluidem does not write through links)" : ""));
}

std::FILE* stream(int fd, const char* mode, const std::string& path, const std::string& what) {
  std::FILE* f = ::fdopen(fd, mode);
  if (f == nullptr) {
    const int err = errno;
    ::close(fd);
    fail(what, path, err);
  }
  return f;
}

std::string parent_of(const std::string& path) {
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return dir.empty() ? "." : dir;
}

} // namespace

Kind kind(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return Kind::missing;
  if (S_ISLNK(st.st_mode)) return Kind::symlink;
  if (S_ISREG(st.st_mode)) return Kind::regular;
  if (S_ISDIR(st.st_mode)) return Kind::directory;
  return Kind::other;
}

const char* to_string(Kind k) {
  switch (k) {
  case Kind::missing:
    return "missing";
  case Kind::regular:
    return "a regular file";
  case Kind::directory:
    return "a directory";
  case Kind::symlink:
    return "a symbolic link";
  case Kind::other:
    break;
  }
  return "not a regular file";
}

std::string temporary_for(const std::string& path) {
  return path + ".tmp";
}

std::FILE* create_exclusive(const std::string& path) {
  if (kind(path) != Kind::missing && kind(path) != Kind::directory) ::unlink(path.c_str());
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) fail("create", path, errno);
  return stream(fd, "wb", path, "create");
}

std::FILE* open_append(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) fail("open for appending", path, errno);
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw OutputError("cannot append to '" + path + "': not a regular file");
  }
  return stream(fd, "ab", path, "open for appending");
}

std::FILE* open_read(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) fail("read", path, errno);
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw OutputError("cannot read '" + path + "': not a regular file");
  }
  return stream(fd, "rb", path, "read");
}

void write_all(std::FILE* f, std::string_view bytes, const std::string& path) {
  if (std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size() || std::fflush(f) != 0)
    fail("write", path, errno);
}

void sync_close(std::FILE* f, const std::string& path) {
  int err = 0;
  if (std::fflush(f) != 0) err = errno;
  if (err == 0 && ::fsync(::fileno(f)) != 0) err = errno;
  if (std::fclose(f) != 0 && err == 0) err = errno;
  if (err != 0) fail("write", path, err);
}

void sync_directory(const std::string& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

void rename_over(const std::string& from, const std::string& to) {
  if (std::rename(from.c_str(), to.c_str()) != 0) {
    const int err = errno;
    remove_quietly(from);
    fail("replace", to, err);
  }
  sync_directory(parent_of(to));
}

void replace(const std::string& path, std::string_view text) {
  const std::string tmp = temporary_for(path);
  std::FILE* f = create_exclusive(tmp);
  try {
    write_all(f, text, tmp);
  } catch (...) {
    std::fclose(f);
    remove_quietly(tmp);
    throw;
  }
  try {
    sync_close(f, tmp);
  } catch (...) {
    remove_quietly(tmp);
    throw;
  }
  rename_over(tmp, path);
}

void copy(const std::string& from, const std::string& to) {
  std::FILE* in = open_read(from);
  std::FILE* out = nullptr;
  try {
    out = create_exclusive(to);
    std::vector<char> buf(1 << 20);
    for (;;) {
      const std::size_t n = std::fread(buf.data(), 1, buf.size(), in);
      if (n > 0) write_all(out, std::string_view(buf.data(), n), to);
      if (n < buf.size()) {
        if (std::ferror(in)) fail("read", from, errno);
        break;
      }
    }
    std::fclose(in);
    in = nullptr;
    std::FILE* done = out;
    out = nullptr;
    sync_close(done, to);
  } catch (...) {
    if (in != nullptr) std::fclose(in);
    if (out != nullptr) std::fclose(out);
    remove_quietly(to);
    throw;
  }
}

void cut(const std::string& path, std::uint64_t bytes) {
  const std::string text = read_all(path);
  if (text.size() < bytes)
    throw OutputError("cannot cut '" + path + "' to " + std::to_string(bytes) +
                      " bytes: it holds " + std::to_string(text.size()));
  if (text.size() == bytes) return;
  replace(path, std::string_view(text).substr(0, bytes));
}

void remove_quietly(const std::string& path) noexcept {
  ::unlink(path.c_str());
}

std::string read_all(const std::string& path) {
  std::FILE* f = open_read(path);
  std::string text;
  std::vector<char> buf(1 << 16);
  for (;;) {
    const std::size_t n = std::fread(buf.data(), 1, buf.size(), f);
    text.append(buf.data(), n);
    if (n < buf.size()) break;
  }
  const bool bad = std::ferror(f) != 0;
  const int err = errno;
  std::fclose(f);
  if (bad) fail("read", path, err);
  return text;
}

std::uint64_t fnv1a(std::string_view bytes, std::uint64_t hash) {
  for (const char c : bytes) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ull;
  }
  return hash;
}

} // namespace fluidem::safe_file
