#include "cueplan/api/output_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

namespace cueplan::api {

std::string ensure_directory(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return "cannot create directory " + dir.string() + ": " + ec.message();
  if (!std::filesystem::is_directory(dir, ec))
    return dir.string() + " exists and is not a directory";
  return {};
}

std::string check_output_file(const std::filesystem::path& path) {
  if (path.empty()) return "no file name given";
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return path.string() + " is a directory";
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : ".";
  const std::filesystem::file_status status = std::filesystem::status(dir, ec);
  if (!std::filesystem::exists(status))
    return "cannot write " + path.string() + ": directory " + dir.string() + " does not exist";
  if (!std::filesystem::is_directory(status))
    return "cannot write " + path.string() + ": " + dir.string() + " is not a directory";
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    return "cannot write " + path.string() + ": " + std::strerror(errno);
  return {};
}

std::string check_picture_file(const std::string& flag, const std::filesystem::path& path) {
  if (!draw::format_of(path))
    return flag + " must name a .svg, .png or .pdf file (the extension chooses the format), got '" +
           path.string() + "'";
  if (std::string why = check_output_file(path); !why.empty()) return flag + ": " + why;
  return {};
}

std::string write_picture(const std::filesystem::path& path, const draw::Picture& picture) {
  const std::optional<draw::Format> format = draw::format_of(path);
  if (!format) return "cannot tell the picture's format from " + path.string();
  const draw::Encoded encoded = draw::encode(picture, *format);
  if (!encoded.ok()) return encoded.error;
  return write_file_atomically(path, encoded.bytes);
}

std::string write_file_atomically(const std::filesystem::path& path, std::string_view contents) {
  // The process id keeps two concurrent writers of the same file apart.
  std::filesystem::path temporary = path;
  temporary += ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) return "cannot write " + temporary.string() + ": " + std::strerror(errno);
    out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    out.close();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      return "cannot write " + temporary.string() + ": " + std::strerror(errno);
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    return "cannot rename " + temporary.string() + " to " + path.string() + ": " + ec.message();
  }
  return {};
}

}  // namespace cueplan::api
