// A run's output directory, held for the run: created when missing and locked exclusively
// (flock(2) on the directory itself, so nothing is left behind), so that two runs, or a run and
// `fluidem analyse`/`plot`, never write into one directory at once. The lock is taken before any
// check of the directory's contents and released when the object goes.
//
// It also knows the names of every file fluidem writes there (result_names()), so that a
// directory holding another run's results is recognised (links and dangling links included),
// a symbolic link under one of those names is refused instead of written through, and `--force`
// removes exactly fluidem's own files.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace fluidem {

class OutputDirectory {
public:
  /// Creates `path` (with its parents) when missing and locks it. `who` says what holds it in
  /// another process's message ("a run", "fluidem analyse"). InputError: an empty path, a path
  /// that cannot be created or is not a directory, a directory locked by another process.
  OutputDirectory(std::string path, std::string who);
  ~OutputDirectory();
  OutputDirectory(OutputDirectory&& other) noexcept;
  OutputDirectory& operator=(OutputDirectory&&) = delete;
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  const std::string& path() const { return path_; }
  /// path()/name.
  std::string file(const std::string& name) const;

  /// The files fluidem writes here (paths relative to the directory): a run's results, their
  /// temporaries, the pictures and analysis of `plot` and `analyse`, the movie and its frames.
  std::vector<std::string> result_names() const;
  /// Those of result_names() that are present (a link counts, dangling or not).
  std::vector<std::string> present_results() const;
  /// The bytes the present regular result files take.
  std::uintmax_t present_bytes() const;
  /// InputError naming the first of result_names() (and analysis/, movie_frames/) that is a
  /// symbolic link, or that is not a regular file (a directory for the two folders).
  void refuse_links() const;
  /// InputError (with the system's reason) unless a file can be created and written here; the
  /// probe file is removed whatever happens.
  void check_writable() const;
  /// Bytes free for this user on the directory's file system (statvfs).
  std::uintmax_t available_bytes() const;
  /// Removes present_results() (links as links), then analysis/ and movie_frames/ when that
  /// left them empty. Call refuse_links() first.
  void remove_results() const;

private:
  std::string path_;
  int fd_ = -1;
};

/// The names of the files a run writes (not the pictures or the analysis).
const std::vector<std::string>& run_file_names();

} // namespace fluidem
