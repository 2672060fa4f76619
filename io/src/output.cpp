#include "heavytop/io/output.hpp"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <iostream>

#include <fcntl.h>
#include <sys/file.h>
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

/// The name of a hidden file beside one called `filename`: "." + filename + suffix, or, when
/// that is longer than a file name may be (NAME_MAX, 255 bytes; a legal 250-byte name would
/// not take ".tmp-XXXXXX"), the name cut short with a hash of the whole name in its place,
/// the same for every process (the lock file must be).
std::string hidden_beside(const std::string& filename, const std::string& suffix) {
  constexpr std::size_t kNameMax = 255;
  if (1 + filename.size() + suffix.size() <= kNameMax) return fmt::format(".{}{}", filename, suffix);
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a
  for (unsigned char c : filename) h = (h ^ c) * 1099511628211ull;
  const std::size_t kept = kNameMax - 1 - 17 - suffix.size();  // 17: "-" and 16 hex digits
  return fmt::format(".{}-{:016x}{}", filename.substr(0, kept), h, suffix);
}

/// A unique temporary file beside `target`, with the mode `target` has (or would get).
/// Returns its path and an open descriptor.
std::pair<std::string, int> temporary_beside(const std::string& target, const std::string& key) {
  const fs::path path(target);
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw InvalidInput(key, fmt::format("the folder '{}' does not exist", dir.string()));
  std::string pattern = (dir / hidden_beside(path.filename().string(), ".tmp-XXXXXX")).string();
  const int fd = ::mkstemp(pattern.data());
  if (fd < 0)
    throw InvalidInput(key, fmt::format("cannot create a file in '{}': {}", dir.string(), std::strerror(errno)));
  struct stat existing {};
  const mode_t mode = ::stat(target.c_str(), &existing) == 0 ? (existing.st_mode & 07777) : new_file_mode();
  ::fchmod(fd, mode);
  return {pattern, fd};
}

/// True if `path` exists and is written directly: not a regular file (a device, a FIFO, a
/// socket, a folder), or a name in /dev or /proc (/dev/stdout, /proc/self/fd/1 name whatever
/// the process writes to, even a regular file it was redirected to: never replace it).
bool is_special(const std::string& path) {
  struct stat s {};
  if (::stat(path.c_str(), &s) != 0) return false;
  if (!S_ISREG(s.st_mode)) return true;
  std::error_code ec;
  const std::string absolute = fs::absolute(path, ec).lexically_normal().string();
  return absolute.starts_with("/dev/") || absolute.starts_with("/proc/");
}



// The temporary and lock files open now, for the signal handler: plain pointers to the paths' bytes
// (owned by their OutputStream), read and unlinked with async-signal-safe calls only.
constexpr std::size_t kSlots = 64;
std::atomic<const char*> g_temporaries[kSlots];

void track(const std::string& path) {
  for (auto& slot : g_temporaries) {
    const char* expected = nullptr;
    if (slot.compare_exchange_strong(expected, path.c_str())) return;
  }
}

void untrack(const std::string& path) {
  for (auto& slot : g_temporaries) {
    const char* expected = path.c_str();
    if (slot.compare_exchange_strong(expected, nullptr)) return;
  }
}

extern "C" void remove_temporaries_and_die(int signal) {
  for (auto& slot : g_temporaries)
    if (const char* path = slot.load()) ::unlink(path);
  ::signal(signal, SIG_DFL);
  ::raise(signal);
}

}  // namespace

void remove_temporaries_on_signals() {
  for (int signal : {SIGINT, SIGTERM, SIGHUP}) ::signal(signal, remove_temporaries_and_die);
}

OutputLock::OutputLock(const std::string& path, const std::string& key, const std::string& shown) {
  const fs::path target(path);
  lock_path_ = (target.parent_path() / hidden_beside(target.filename().string(), ".lock")).string();
  for (;;) {
    fd_ = ::open(lock_path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd_ < 0) {
      std::error_code ec;
      if (!fs::is_directory(target.has_parent_path() ? target.parent_path() : fs::path("."), ec))
        throw InvalidInput(key, fmt::format("the folder of '{}' does not exist", path));
      throw InvalidInput(key, fmt::format("cannot write beside '{}': {}", path, std::strerror(errno)));
    }
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd_);
      fd_ = -1;
      throw InvalidInput(key, fmt::format("'{}' is being written by another process; wait for it to finish",
                                          shown.empty() ? path : shown));
    }
    // The lock file may have been removed by its previous holder between our open and flock:
    // then ours is a stale inode, and we start again.
    struct stat held {}, now {};
    if (::fstat(fd_, &held) == 0 && ::stat(lock_path_.c_str(), &now) == 0 && held.st_ino == now.st_ino &&
        held.st_dev == now.st_dev) {
      track(lock_path_);
      return;
    }
    ::close(fd_);
  }
}

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  untrack(lock_path_);
  ::unlink(lock_path_.c_str());
  ::close(fd_);
}

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
  path_ = resolved(path_);
  lock_.emplace(path_, key_);
  auto [temporary, fd] = temporary_beside(path_, key_);
  temporary_ = std::move(temporary);
  track(temporary_);
  file_ = ::fdopen(fd, "wb");
  if (!file_) {
    ::close(fd);
    ::unlink(temporary_.c_str());
    throw Failure(fmt::format("{}: cannot write '{}'", key_, printable(path_)));
  }
  owns_file_ = true;
}

OutputStream::~OutputStream() {
  if (owns_file_ && file_) std::fclose(file_);
  if (!temporary_.empty()) {
    if (!committed_) ::unlink(temporary_.c_str());
    untrack(temporary_);
  }
}

void OutputStream::write(std::string_view text) {
  if (text.empty()) return;
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size())
    throw Failure(fmt::format("{}: cannot write '{}': {}", key_, path_.empty() ? "stdout" : printable(path_), std::strerror(errno)));
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

std::string resolved(const std::string& path) {
  std::error_code ec;
  if (!fs::is_symlink(path, ec)) return path;
  // Link by link (a dangling link's target is the file to create, not the link to replace;
  // weakly_canonical() stops at a name that does not exist and so gave the link itself).
  fs::path p(path);
  for (int hops = 0; hops < 40 && fs::is_symlink(p, ec); ++hops) {
    const fs::path target = fs::read_symlink(p, ec);
    if (ec) return path;
    p = target.is_absolute() ? target : (p.parent_path() / target);
  }
  if (fs::is_symlink(p, ec)) return path;  // a loop: left to the caller's open() to refuse
  // The real folder (its own links resolved) and the final name.
  const fs::path folder = fs::weakly_canonical(p.has_parent_path() ? p.parent_path() : fs::path("."), ec);
  return ec ? p.lexically_normal().string() : (folder / p.filename()).string();
}

bool is_regular_target(const std::string& path) { return !path.empty() && path != "-" && !is_special(path); }

void copy_mode(const std::string& target, const std::string& file) {
  struct stat existing {};
  if (::stat(target.c_str(), &existing) == 0) ::chmod(file.c_str(), existing.st_mode & 07777);
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
  track(temporary);
  struct Untrack {
    const std::string& path;
    ~Untrack() { untrack(path); }
  } untrack_at_exit{temporary};
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
