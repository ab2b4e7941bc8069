#include "output/output_directory.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <utility>

#include <fmt/format.h>

#include "core/error.hpp"
#include "output/safe_file.hpp"

namespace fluidem {

namespace fs = std::filesystem;

namespace {

// `fluidem analyse` (src/app/analyse*.cpp) and python/fluidem_analysis_plot.py write these into
// analysis/; spectrum_<probe>.csv/.png are matched by prefix.
const char* const kAnalysisFiles[] = {
    "summary.csv",     "velocity_distribution.csv",  "velocity_distribution.png", "segregation.csv",
    "segregation.png", "pressure_drop_velocity.csv", "pressure_drop_velocity.png"};

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}
bool starts_with(const std::string& s, const std::string& head) {
  return s.rfind(head, 0) == 0;
}

bool analysis_file(const std::string& name) {
  if (std::find(std::begin(kAnalysisFiles), std::end(kAnalysisFiles), name) !=
      std::end(kAnalysisFiles))
    return true;
  return starts_with(name, "spectrum_") && (ends_with(name, ".csv") || ends_with(name, ".png"));
}

bool movie_frame(const std::string& name) {
  return starts_with(name, "frame_") && ends_with(name, ".png");
}

// The entries of `dir` that `match` (not following links; empty when dir is not a directory).
std::vector<std::string> entries(const fs::path& dir, bool (*match)(const std::string&)) {
  std::vector<std::string> names;
  if (safe_file::kind(dir.string()) != safe_file::Kind::directory) return names;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (match(name)) names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

} // namespace

const std::vector<std::string>& run_file_names() {
  static const std::vector<std::string> names{"case.resolved.toml",
                                              "particles.h5",
                                              "particles.xmf",
                                              "series.csv",
                                              "fields.h5",
                                              "fields.xmf",
                                              "probes.csv",
                                              "checkpoint.h5",
                                              "checkpoint.prev.h5",
                                              "collisions.csv",
                                              "collision_overlap.csv",
                                              "continuum.h5",
                                              "continuum.xmf",
                                              "snapshot.png",
                                              "movie.mp4"};
  return names;
}

OutputDirectory::OutputDirectory(std::string path, std::string who) : path_(std::move(path)) {
  if (path_.empty())
    throw InputError("the output directory is an empty path (give --out DIR, or leave --out out "
                     "for the default out/<case name>)");
  std::error_code ec;
  fs::create_directories(path_, ec);
  if (ec && !fs::is_directory(path_))
    throw InputError(
        fmt::format("cannot create the output directory '{}': {}", path_, ec.message()));
  fd_ = ::open(path_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd_ < 0)
    throw InputError(fmt::format("cannot use '{}' as the output directory: {}", path_,
                                 errno == ENOTDIR ? "it is not a directory"
                                                  : std::string(std::strerror(errno))));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    ::close(fd_);
    fd_ = -1;
    if (err == EWOULDBLOCK)
      throw InputError(fmt::format(
          "the output directory '{}' is in use by another fluidem process (a run, or analyse or "
          "plot writing into it), so {} cannot write there: let it finish, or use another "
          "directory",
          path_, who));
    throw InputError(
        fmt::format("cannot lock the output directory '{}': {}", path_, std::strerror(err)));
  }
}

OutputDirectory::~OutputDirectory() {
  if (fd_ >= 0) ::close(fd_); // releases the lock
}

OutputDirectory::OutputDirectory(OutputDirectory&& o) noexcept
    : path_(std::move(o.path_)), fd_(std::exchange(o.fd_, -1)) {}

std::string OutputDirectory::file(const std::string& name) const {
  return (fs::path(path_) / name).string();
}

std::vector<std::string> OutputDirectory::result_names() const {
  std::vector<std::string> names;
  for (const std::string& f : run_file_names()) {
    names.push_back(f);
    names.push_back(safe_file::temporary_for(f));
  }
  for (const char* a : kAnalysisFiles) names.push_back(std::string("analysis/") + a);
  for (const std::string& a : entries(fs::path(path_) / "analysis", analysis_file))
    if (std::find(names.begin(), names.end(), "analysis/" + a) == names.end())
      names.push_back("analysis/" + a);
  for (const std::string& m : entries(fs::path(path_) / "movie_frames", movie_frame))
    names.push_back("movie_frames/" + m);
  return names;
}

std::vector<std::string> OutputDirectory::present_results() const {
  std::vector<std::string> found;
  for (const std::string& name : result_names())
    if (safe_file::kind(file(name)) != safe_file::Kind::missing) found.push_back(name);
  return found;
}

std::uintmax_t OutputDirectory::present_bytes() const {
  std::uintmax_t bytes = 0;
  for (const std::string& name : present_results()) {
    std::error_code ec;
    if (safe_file::kind(file(name)) == safe_file::Kind::regular) {
      const auto size = fs::file_size(file(name), ec);
      if (!ec) bytes += size;
    }
  }
  return bytes;
}

void OutputDirectory::refuse_links() const {
  for (const char* folder : {"analysis", "movie_frames"}) {
    const safe_file::Kind k = safe_file::kind(file(folder));
    if (k != safe_file::Kind::missing && k != safe_file::Kind::directory)
      throw InputError(fmt::format("'{}' is {}: fluidem writes its {} there; remove it or use "
                                   "another output directory",
                                   file(folder), safe_file::to_string(k), folder));
  }
  for (const std::string& name : result_names()) {
    const safe_file::Kind k = safe_file::kind(file(name));
    if (k == safe_file::Kind::missing || k == safe_file::Kind::regular) continue;
    throw InputError(fmt::format(
        "'{}' is {}: fluidem writes its own file under that name and never writes through a "
        "link or over something else; remove it, or use another output directory",
        file(name), safe_file::to_string(k)));
  }
}

void OutputDirectory::check_writable() const {
  const std::string probe = file(fmt::format(".fluidem-write-test.{}", ::getpid()));
  try {
    std::FILE* f = safe_file::create_exclusive(probe);
    safe_file::write_all(f, "x", probe);
    if (std::fclose(f) != 0) throw OutputError(std::strerror(errno));
  } catch (const OutputError& e) {
    safe_file::remove_quietly(probe);
    throw InputError(fmt::format("cannot write to the output directory '{}': {}", path_, e.what()));
  }
  safe_file::remove_quietly(probe);
}

std::uintmax_t OutputDirectory::available_bytes() const {
  std::error_code ec;
  const fs::space_info space = fs::space(path_, ec);
  return ec ? static_cast<std::uintmax_t>(-1) : space.available;
}

void OutputDirectory::remove_results() const {
  for (const std::string& name : present_results()) safe_file::remove_quietly(file(name));
  for (const char* folder : {"analysis", "movie_frames"}) {
    std::error_code ec;
    if (safe_file::kind(file(folder)) == safe_file::Kind::directory && fs::is_empty(file(folder)))
      fs::remove(file(folder), ec);
  }
}

} // namespace fluidem
