#include "scene/input_file.h"

#include <filesystem>
#include <fstream>
#include <iterator>

namespace scour {

namespace fs = std::filesystem;

size_t checkInputFile(const std::string& path, const std::string& what, size_t maxBytes) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st)) throw InputFileError(path + ": cannot open the " + what);
  if (fs::is_directory(st)) throw InputFileError(path + ": is a directory, not a " + what);
  if (!fs::is_regular_file(st)) throw InputFileError(path + ": is not a regular file (a " + what + " is expected)");
  const uintmax_t size = fs::file_size(path, ec);
  if (ec) throw InputFileError(path + ": cannot open the " + what + ": " + ec.message());
  if (size > maxBytes)
    throw InputFileError(path + ": the " + what + " is " + std::to_string(size) + " bytes, more than the " +
                         std::to_string(maxBytes) + " this build reads");
  return size_t(size);
}

std::string readInputFile(const std::string& path, const std::string& what, size_t maxBytes) {
  checkInputFile(path, what, maxBytes);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputFileError(path + ": cannot open the " + what);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputFileError(path + ": cannot read the " + what);
  return bytes;
}

}  // namespace scour
