// Input files a case names (the case file itself, LAMMPS data files): what stops a path from
// being read, in words, with the system's reason, instead of "file not found" for a folder or a
// device, or a bare "cannot open".
#pragma once
#include <optional>
#include <string>

namespace fluidem {

/// Why `path` cannot be read as an input file, or nothing when it can: "does not exist", "is a
/// directory, not a file", "is a character device, not a regular file", "cannot be opened:
/// Permission denied" (the system's reason, strerror(errno)). A named pipe is accepted when
/// `allow_pipe` (a case file given as <(...)); it is not opened here (that would wait for a
/// writer).
std::optional<std::string> input_file_problem(const std::string& path, bool allow_pipe = false);

/// "cannot be read: <the system's reason for errno>", for a read that failed after the open.
std::string read_failure(int errno_value);

} // namespace fluidem
