// libFuzzer target: the heavytop command line, cli::run() in-process (cli/app.hpp), on
// arbitrary argument lists.
//
// The input is split into arguments at every newline or NUL byte (at most 16; a trailing
// separator ends the last one) and "heavytop" is put in front. Exit statuses 0, 1 and 2 are
// all fine; a finding is a crash, undefined behaviour or an address error (the sanitizers), a
// leak, an exception escaping run(), an abort, an exit status other than 0, 1 or 2, or a file
// left in (or missing from) the private folder after the run.
//
// Each run must be fast and harmless (we may be root), so inputs that could start expensive
// or outside work are skipped (return -1: not run, not kept in the corpus). Skipped are:
//   - more than 16 arguments;
//   - no command: the built-in report would be written (gnuplot, seconds); allowed only with
//     -h/--help or an argument that cannot parse at the top level (not starting with '-');
//   - more than one argument spelled like a command (stability, simulate, compare, sweep),
//     any argument `report` (it draws figures with gnuplot) and any argument `derive` (heavytop
//     runs the program heavytop-derive for it, which is not in-process and not beside the
//     fuzzer);
//   - `--output` in any form (it writes files, possibly outside the private folder);
//   - paths outside the private folder: an argument starting with '/' or '~', or holding
//     "=/" or ".." (--config /dev/stdin would block);
//   - a --samples value that is a number above 2000, a --max-steps value above 20000 (1000
//     for sweep), a sweep COUNT (after the last ':' of any argument) above 8 -- "a number": any
//     value with a digit in it that is not plain decimal digits is skipped too, so that
//     CLI11's hexadecimal, octal, binary or signed spellings cannot slip a large one past;
//   - a second --model.
// And the integrating commands are bounded: `compare`, `sweep` and `simulate` of the nonlinear
// model (no --model, or --model nonlinear) get `--max-steps 20000` (sweep: 1000, per point)
// appended when they have no --max-steps, so the adaptive and the splitting integrators stop
// there (exit 1). The sweep runs on every core.
//
// Each run happens in a private temporary folder holding a few configuration files (top.toml,
// sim.toml, bad.toml, unknown.toml, nan.toml) and a folder (dir), removed at exit. stdout goes
// to /dev/null and std::cerr is discarded (HEAVYTOP_FUZZ_VERBOSE=1 keeps both); libFuzzer's
// and the sanitizers' reports still reach stderr. PATH is emptied, so that nothing run can
// start a program (gnuplot). run() installs heavytop's SIGINT/SIGTERM/SIGHUP handlers over
// libFuzzer's: Ctrl-C stops the fuzzer without its final statistics (-max_total_time is
// unaffected).
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <streambuf>
#include <string>
#include <string_view>
#include <vector>

#include "app.hpp"

namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxArguments = 16;
constexpr long kMaxSamples = 2000;
constexpr long kMaxSteps = 20000;      // simulate, compare: one run
constexpr long kMaxSweepSteps = 1000;  // sweep: per grid point, up to 64 points
constexpr long kMaxCount = 8;

const char* const kCommands[] = {"stability", "simulate", "compare", "sweep"};

fs::path private_folder;
int home_folder = -1;  // the folder libFuzzer was started in

class NullBuffer : public std::streambuf {
 protected:
  int overflow(int c) override { return c == traits_type::eof() ? 0 : c; }
  std::streamsize xsputn(const char*, std::streamsize n) override { return n; }
};
NullBuffer null_buffer;

std::string initial_listing;

// The private folder's names, recursively, sorted.
std::string listing() {
  std::vector<std::string> names;
  for (const auto& entry : fs::recursive_directory_iterator(private_folder))
    names.push_back(fs::relative(entry.path(), private_folder).string());
  std::sort(names.begin(), names.end());
  std::string all;
  for (const std::string& n : names) all += n + "\n";
  return all;
}

void write_file(const fs::path& path, std::string_view text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

void remove_private_folder() {
  std::error_code ignored;
  if (!private_folder.empty()) fs::remove_all(private_folder, ignored);
}

bool is_command(const std::string& a) {
  for (const char* c : kCommands)
    if (a == c) return true;
  return false;
}

// A value of a costly option: fine if it has no digit (CLI11 refuses it) or is plain decimal
// digits no larger than `bound`; anything else (a large number, 0x.., -1, 1e9, " 5") is skipped.
bool small_or_not_a_number(std::string_view v, long bound) {
  bool digit = false, plain = !v.empty() && v.size() <= 7;
  for (char c : v) {
    const bool d = c >= '0' && c <= '9';
    digit = digit || d;
    plain = plain && d;
  }
  if (!digit) return true;
  return plain && std::stol(std::string(v)) <= bound;
}

// The value of option `name` at argument i (attached "--name=v" or the next argument); the
// bounds hold for every candidate.
bool option_values_ok(const std::vector<std::string>& args, const std::string& name, long bound) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == name) {
      if (i + 1 < args.size() && !small_or_not_a_number(args[i + 1], bound)) return false;
    } else if (a.starts_with(name + "=")) {
      if (!small_or_not_a_number(std::string_view(a).substr(name.size() + 1), bound)) return false;
    }
  }
  return true;
}

bool gives(const std::vector<std::string>& args, const std::string& name) {
  for (const std::string& a : args)
    if (a == name || a.starts_with(name + "=")) return true;
  return false;
}

// The arguments to run (after "heavytop"), or false to skip the input.
bool arguments_to_run(std::vector<std::string>& args) {
  if (args.size() > kMaxArguments) return false;
  std::string command;
  int commands = 0, models = 0;
  bool help = false, positional = false;
  std::string model = "nonlinear";
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "report" || a == "derive" || a.starts_with("--output")) return false;
    if (a.starts_with("/") || a.starts_with("~") || a.find("=/") != std::string::npos ||
        a.find("..") != std::string::npos)
      return false;
    if (is_command(a)) {
      ++commands;
      command = a;
    }
    if (a == "-h" || a == "--help") help = true;
    if (!a.empty() && a[0] != '-') positional = true;
    if (a == "--model" || a.starts_with("--model=")) {
      ++models;
      if (a == "--model") model = i + 1 < args.size() ? args[i + 1] : "";
      else model = a.substr(8);
    }
    if (const auto colon = a.rfind(':'); colon != std::string::npos &&
                                         !small_or_not_a_number(std::string_view(a).substr(colon + 1), kMaxCount))
      return false;
  }
  if (commands > 1 || models > 1) return false;
  if (commands == 0 && !help && !positional) return false;
  const long max_steps = command == "sweep" ? kMaxSweepSteps : kMaxSteps;
  if (!option_values_ok(args, "--samples", kMaxSamples) || !option_values_ok(args, "--max-steps", max_steps))
    return false;
  const bool integrates = command == "compare" || command == "sweep" || (command == "simulate" && model == "nonlinear");
  if (integrates && !gives(args, "--max-steps")) {
    args.emplace_back("--max-steps");
    args.emplace_back(std::to_string(max_steps));
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  char folder[] = "/tmp/heavytop-fuzz-cli-XXXXXX";
  if (!::mkdtemp(folder)) {
    std::perror("fuzz_cli: mkdtemp");
    std::exit(1);
  }
  private_folder = folder;
  std::atexit(remove_private_folder);
  // libFuzzer reads and writes the corpus relative to the folder it was started in: the runs
  // go to the private folder and come back (fchdir), Initialize only fills it.
  home_folder = ::open(".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (home_folder < 0) {
    std::perror("fuzz_cli: open .");
    std::exit(1);
  }
  fs::current_path(private_folder);
  write_file("top.toml",
             "[body]\nA = 4.35e-5\nB = 4.35e-5\nC = 1.2e-5\nmass = 0.060\nlength = 0.025\n"
             "[motion]\nspin = 200.0\ntheta0 = 0.05\n");
  write_file("sim.toml",
             "[body]\nA = 1.0\nB = 1.0\nC = 2.0\nmass = 1.0\nlength = 1.0\n[motion]\nspin = 3.0\ntheta0 = 0.01\n"
             "[simulate]\nt_end = 2.0\nsamples = 11\nrtol = 1e-8\n");
  write_file("bad.toml", "[body\nA = = 1\n");
  write_file("unknown.toml", "[body]\nA = 1\nB = 1\nC = 1\nmass = 1\nlength = 1\nwidth = 2\n");
  write_file("nan.toml", "[body]\nA = nan\nB = inf\nC = -1\nmass = 1e308\nlength = 1e308\n[motion]\nspin = -inf\n");
  fs::create_directory("dir");
  initial_listing = listing();
  ::setenv("PATH", (private_folder / "dir").c_str(), 1);
  if (!std::getenv("HEAVYTOP_FUZZ_VERBOSE")) {
    const int null = ::open("/dev/null", O_WRONLY);
    if (null >= 0) ::dup2(null, STDOUT_FILENO);
    std::cout.rdbuf(&null_buffer);
    std::cerr.rdbuf(&null_buffer);
  }
  if (::fchdir(home_folder) != 0) std::abort();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> args;
  std::string current;
  bool open = false;
  for (std::size_t i = 0; i < size; ++i) {
    const char c = static_cast<char>(data[i]);
    if (c == '\n' || c == '\0') {
      args.push_back(current);
      current.clear();
      open = false;
      if (args.size() > kMaxArguments) return -1;
    } else {
      current += c;
      open = true;
    }
  }
  if (open) args.push_back(current);
  if (!arguments_to_run(args)) return -1;

  std::vector<std::string> storage{"heavytop"};
  storage.insert(storage.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& s : storage) argv.push_back(s.data());
  argv.push_back(nullptr);

  fs::current_path(private_folder);
  const int status = heavytop::cli::run(static_cast<int>(storage.size()), argv.data());
  std::fflush(stdout);
  if (::fchdir(home_folder) != 0) std::abort();
  if (status != 0 && status != 1 && status != 2) {
    std::fprintf(stderr, "fuzz_cli: exit status %d, not 0, 1 or 2\n", status);
    std::abort();
  }
  // No --output is run, so the private folder must hold what it held (no lock, temporary or
  // partial file left behind, no report written).
  if (listing() != initial_listing) {
    std::fprintf(stderr, "fuzz_cli: the run changed the private folder %s\n", private_folder.c_str());
    std::abort();
  }
  return 0;
}
