#pragma once
/// \file
/// Where results go: stdout, a device or pipe (written directly, never replaced), or a regular
/// file (written to a unique temporary name in the same folder and renamed over the target,
/// so a failure never leaves a partial file). SPEC section 1.

#include <cstdio>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace heavytop::io {

/// Internal or numerical failure of an output (exit status 1); bad input is InvalidInput.
struct Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// An exclusive lock on an output path, held while it is written, so that a second writer
/// of the same path is refused instead of interleaving (SPEC section 1). It is an flock() on
/// a lock file beside the target (".NAME.lock"), removed again when released.
class OutputLock {
 public:
  /// Takes the lock of `path` or throws InvalidInput(key, "'<shown>' is being written by
  /// another process") at once if another process holds it (`shown` defaults to `path`).
  OutputLock(const std::string& path, const std::string& key, const std::string& shown = "");
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;
  ~OutputLock();

 private:
  std::string lock_path_;
  int fd_ = -1;
};

/// Removes the temporary files of every OutputStream still open when the process gets
/// SIGINT, SIGTERM or SIGHUP, then dies of that signal as it would have (call once, early).
void remove_temporaries_on_signals();

/// A stream to one output. `path` "" or "-" is stdout; a path that exists and is not a
/// regular file (a device, a FIFO, a terminal) is opened and written directly; any other
/// path gets a temporary file beside it, created with the mode the target would get (that
/// of an existing file, else 0666 less the umask), which commit() renames over the target.
/// Destroyed without commit(), the temporary file is removed and the target is untouched.
/// A regular target is locked (OutputLock) from construction to destruction.
/// `key` names the setting in messages ("--output" for the CLI).
class OutputStream {
 public:
  OutputStream(std::string path, std::string key);
  OutputStream(const OutputStream&) = delete;
  OutputStream& operator=(const OutputStream&) = delete;
  ~OutputStream();

  /// Appends `text`. Throws Failure if it cannot be written.
  void write(std::string_view text);
  /// Flushes and, for a regular file, renames the temporary file over the target.
  void commit();
  /// True if writes go through a temporary file (the target is a regular file or absent).
  bool atomic() const noexcept { return !temporary_.empty(); }
  /// The path being written now: the temporary file's, else the target's ("" for stdout).
  const std::string& writing_path() const noexcept { return atomic() ? temporary_ : path_; }

 private:
  std::string path_;
  std::string key_;
  std::optional<OutputLock> lock_;
  std::string temporary_;
  std::FILE* file_ = nullptr;
  bool owns_file_ = false;
  bool committed_ = false;
};

/// True if `path` ("" and "-" being stdout) is written through a temporary file and a
/// rename: it names a regular file or nothing yet.
bool is_regular_target(const std::string& path);

/// The file a path names: a symbolic link's target (a file written through a temporary name
/// and a rename replaces the target, and the link stays a link), else the path itself.
std::string resolved(const std::string& path);

/// Gives `file` the mode `target` has, if `target` exists (so that replacing a file keeps its
/// permissions).
void copy_mode(const std::string& target, const std::string& file);

/// Writes `content` to `path` as OutputStream does, in one go.
void write_output(const std::string& path, const std::string& content, const std::string& key = "--output");

/// Writes a regular file through a temporary name and a rename; `fill` writes the content to
/// the temporary path it is given (for files made by other programs, such as gnuplot). The
/// caller holds the output's lock if one is needed.
void write_atomically(const std::string& path, const std::function<void(const std::string&)>& fill,
                      const std::string& key = "--output");

}  // namespace heavytop::io
