#include "bssrdf/io/atomic_file.hpp"

#include <unistd.h>
#include <cstdio>
#include <fstream>

#include "bssrdf/error.hpp"

namespace bssrdf {
namespace {

// Writes straight into `path` (a device, a FIFO): these have no content to protect and must never be
// replaced by a regular file.
void write_directly(const std::filesystem::path& path, std::string_view content) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw FileError(path.string(), 0, "cannot write: cannot open this special file");
  out.write(content.data(), static_cast<std::streamsize>(content.size()));
  out.flush();
  if (!out) throw FileError(path.string(), 0, "writing failed");
}

}  // namespace

void write_file_atomically(const std::filesystem::path& requested, std::string_view content) {
  if (requested.empty()) throw FileError("''", 0, "cannot write: the output file name is empty");
  std::error_code ec;
  // A symlink: the user means the file it names, so that file is replaced and the link kept.
  std::filesystem::path path = requested;
  if (std::filesystem::is_symlink(requested, ec)) {
    path = std::filesystem::weakly_canonical(requested, ec);
    if (ec) throw FileError(requested.string(), 0, "cannot write: cannot resolve the symbolic link");
  }
  const auto status = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(status)) throw FileError(requested.string(), 0, "cannot write: it is a directory");
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    return write_directly(path, content);

  const auto directory = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  if (!std::filesystem::is_directory(directory, ec))
    throw FileError(requested.string(), 0, "cannot write: directory '" + directory.string() + "' does not exist");
  const auto temporary = std::filesystem::path(path.string() + ".tmp." + std::to_string(::getpid()));
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw FileError(requested.string(), 0, "cannot write the output file");
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.flush();
    if (!out) {
      out.close();
      std::filesystem::remove(temporary, ec);
      throw FileError(requested.string(), 0, "writing failed (disk full?)");
    }
  }
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::filesystem::remove(temporary, ec);
    throw FileError(requested.string(), 0, "cannot move the finished file into place");
  }
}

}  // namespace bssrdf
