#include "bssrdf/io/atomic_file.hpp"

#include <cstdio>
#include <fstream>
#include <random>
#include <unistd.h>

#include "bssrdf/error.hpp"

namespace bssrdf {

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  const auto directory = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  if (!std::filesystem::is_directory(directory, ec))
    throw FileError(path.string(), 0, "cannot write: directory '" + directory.string() + "' does not exist");
  const auto temporary = std::filesystem::path(path.string() + ".tmp." + std::to_string(::getpid()));
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw FileError(path.string(), 0, "cannot write the output file");
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.flush();
    if (!out) {
      out.close();
      std::filesystem::remove(temporary, ec);
      throw FileError(path.string(), 0, "writing failed (disk full?)");
    }
  }
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::filesystem::remove(temporary, ec);
    throw FileError(path.string(), 0, "cannot move the finished file into place");
  }
}

}  // namespace bssrdf
