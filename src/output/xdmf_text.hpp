// Text helpers shared by the XDMF indexes (particles.xmf, fields.xmf).
#pragma once
#include <string>

namespace fluidem::xdmf_text {

/// s with the five XML special characters escaped.
std::string xml_escape(const std::string& s);
/// Shortest text that reads back as the same double.
std::string shortest(double v);
/// Writes `text` to `path` atomically (safe_file::replace: a temporary file `path.tmp`, synced,
/// then a rename; never through a link), so that a reader never sees a half-written index.
/// OutputError naming the file on failure.
void write_file_atomically(const std::string& path, const std::string& text);

} // namespace fluidem::xdmf_text
