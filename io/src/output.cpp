#include "heavytop/io/output.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include "heavytop/body.hpp"

namespace heavytop::io {
namespace {

namespace fs = std::filesystem;

/// The mode a new file gets from open(..., 0666): 0666 less the process's umask.
mode_t new_file_mode() {
  static const mode_t mode = [] {
    const mode_t mask = ::umask(0);
    ::umask(mask);
    return static_cast<mode_t>(0666 & ~mask);
  }();
  return mode;
}

/// A unique temporary file beside `target`, with the mode `target` has (or would get).
/// Returns its path and an open descriptor.
std::pair<std::string, int> temporary_beside(const std::string& target, const std::string& key) {
  const fs::path path(target);
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw InvalidInput(key, fmt::format("the folder '{}' does not exist", dir.string()));
  std::string pattern = (dir / ("." + path.filename().string() + ".tmp-XXXXXX")).string();
  const int fd = ::mkstemp(pattern.data());
  if (fd < 0)
    throw InvalidInput(key, fmt::format("cannot create a file in '{}': {}", dir.string(), std::strerror(errno)));
  struct stat existing {};
  const mode_t mode = ::stat(target.c_str(), &existing) == 0 ? (existing.st_mode & 07777) : new_file_mode();
  ::fchmod(fd, mode);
  return {pattern, fd};
}

/// True if `path` exists and is not a regular file (or a link to one).
bool is_special(const std::string& path) {
  struct stat s {};
  return ::stat(path.c_str(), &s) == 0 && !S_ISREG(s.st_mode);
}

}  // namespace

OutputStream::OutputStream(std::string path, std::string key) : path_(std::move(path)), key_(std::move(key)) {
  if (path_.empty() || path_ == "-") {
    file_ = stdout;
    path_.clear();
    return;
  }
  if (is_special(path_)) {
    struct stat s {};
    ::stat(path_.c_str(), &s);
    if (S_ISDIR(s.st_mode)) throw InvalidInput(key_, fmt::format("'{}' is a folder", path_));
    file_ = std::fopen(path_.c_str(), "wb");
    if (!file_) throw InvalidInput(key_, fmt::format("cannot write '{}': {}", path_, std::strerror(errno)));
    owns_file_ = true;
    return;
  }
  auto [temporary, fd] = temporary_beside(path_, key_);
  temporary_ = std::move(temporary);
  file_ = ::fdopen(fd, "wb");
  if (!file_) {
    ::close(fd);
    ::unlink(temporary_.c_str());
    throw Failure(fmt::format("{}: cannot write '{}'", key_, path_));
  }
  owns_file_ = true;
}

OutputStream::~OutputStream() {
  if (owns_file_ && file_) std::fclose(file_);
  if (!committed_ && !temporary_.empty()) ::unlink(temporary_.c_str());
}

void OutputStream::write(std::string_view text) {
  if (text.empty()) return;
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size())
    throw Failure(fmt::format("{}: cannot write '{}': {}", key_, path_.empty() ? "stdout" : path_, std::strerror(errno)));
}

void OutputStream::commit() {
  if (std::fflush(file_) != 0)
    throw Failure(fmt::format("{}: cannot write '{}': {}", key_, path_.empty() ? "stdout" : path_, std::strerror(errno)));
  if (owns_file_) {
    const int closed = std::fclose(file_);
    file_ = nullptr;
    if (closed != 0) throw Failure(fmt::format("{}: cannot write '{}': {}", key_, path_, std::strerror(errno)));
  }
  if (!temporary_.empty() && std::rename(temporary_.c_str(), path_.c_str()) != 0)
    throw Failure(fmt::format("{}: cannot replace '{}': {}", key_, path_, std::strerror(errno)));
  committed_ = true;
}

void write_output(const std::string& path, const std::string& content, const std::string& key) {
  OutputStream out(path, key);
  out.write(content);
  out.commit();
}

void write_atomically(const std::string& path, const std::function<void(const std::string&)>& fill,
                      const std::string& key) {
  auto [temporary, fd] = temporary_beside(path, key);
  ::close(fd);
  try {
    fill(temporary);
    if (std::rename(temporary.c_str(), path.c_str()) != 0)
      throw Failure(fmt::format("{}: cannot replace '{}': {}", key, path, std::strerror(errno)));
  } catch (...) {
    ::unlink(temporary.c_str());
    throw;
  }
}

}  // namespace heavytop::io
