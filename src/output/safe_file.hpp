// Files written so that a crash, a full disk or a planted symbolic link can never cut, mix or
// redirect them. Every function here opens with O_NOFOLLOW (a symbolic link at the final path
// component is refused, never followed), creates temporaries with O_EXCL (a name that exists,
// even a dangling link, is removed as a name first: unlink does not follow links), and replaces
// a file only by rename(2) of a complete, fsync'ed temporary, followed by an fsync of the
// directory. Failures throw OutputError naming the file and the system's reason (errno).
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

#include "core/error.hpp"

namespace fluidem::safe_file {

/// What is at `path` without following a link there.
enum class Kind { missing, regular, directory, symlink, other };
Kind kind(const std::string& path);
const char* to_string(Kind k);

/// The temporary name used to replace `path`: "<path>.tmp".
std::string temporary_for(const std::string& path);

/// A new file at `path` opened for writing: any entry at `path` that is not a directory is
/// unlinked first, then the file is created with O_CREAT | O_EXCL | O_NOFOLLOW (mode 0644).
/// For temporaries only: the caller owns that name.
std::FILE* create_exclusive(const std::string& path);

/// Opens the existing regular file `path` for appending (O_NOFOLLOW: a link is refused).
std::FILE* open_append(const std::string& path);

/// Opens the existing file `path` for reading (O_NOFOLLOW). OutputError if it is a link, not a
/// regular file, or unreadable.
std::FILE* open_read(const std::string& path);

/// Writes `bytes` to `f` and flushes it (OutputError naming `path`, with errno, on failure).
void write_all(std::FILE* f, std::string_view bytes, const std::string& path);

/// fflush + fsync + fclose; OutputError naming `path` on failure (the stream is closed anyway).
void sync_close(std::FILE* f, const std::string& path);

/// fsync of a directory (best effort: some file systems refuse it).
void sync_directory(const std::string& dir);

/// Replaces `path` by a file holding `text`: temporary_for(path) created exclusively, written,
/// synced, renamed over `path`, the directory synced. On failure the temporary is removed and
/// `path` is as it was.
void replace(const std::string& path, std::string_view text);

/// Replaces `path` by a copy of its first `bytes` bytes, the same way (nothing is written when
/// the file already has exactly that size). OutputError if it is shorter.
void cut(const std::string& path, std::uint64_t bytes);

/// Copies the regular file `from` (O_NOFOLLOW) to the new file `to` (create_exclusive) and syncs
/// it. On failure `to` is removed.
void copy(const std::string& from, const std::string& to);

/// Renames `from` over `to` (rename(2): a link at `to` is replaced, not followed) and syncs the
/// directory of `to`.
void rename_over(const std::string& from, const std::string& to);

/// Removes `path` if it is there (a link is removed as a link); no error if it is missing.
void remove_quietly(const std::string& path) noexcept;

/// The whole regular file `path` (open_read).
std::string read_all(const std::string& path);

/// 64-bit FNV-1a of `bytes`, continuing from `hash` (start with kFnvOffset).
inline constexpr std::uint64_t kFnvOffset = 14695981039346656037ull;
std::uint64_t fnv1a(std::string_view bytes, std::uint64_t hash = kFnvOffset);

} // namespace fluidem::safe_file
