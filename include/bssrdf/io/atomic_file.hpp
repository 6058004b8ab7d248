// Output files are written to a temporary file beside the target and renamed into place, so a
// failure (bad input found late, a full disk, an interrupted run) never leaves a partial file.
// A symbolic link is followed (the file it names is replaced, the link kept); a device or FIFO
// (e.g. /dev/null, /dev/stdout) is written directly, never replaced.
#pragma once

#include <filesystem>
#include <string_view>

namespace bssrdf {

// Throws FileError when the file cannot be written; the target is then untouched.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace bssrdf
