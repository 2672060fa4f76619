// heavytop sweep: a stability map over one to three parameters, resumable when written to a file.
//
// With --output FILE the rows go to FILE.partial as they are computed (in grid order, whole
// records), beside FILE.partial.args, which records the arguments. Run again with the same
// arguments after an interruption and it goes on from the last complete record; at the end
// FILE.partial becomes FILE (renamed for CSV; for HDF5 the columnar file is written from it
// through a temporary name). Nothing is lost or written twice. Under MPI (heavytop-mpi) the
// ranks compute the blocks and the first rank alone does all of this.
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <fmt/format.h>

#include "commands.hpp"
#include "common.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/io/map_file.hpp"
#include "heavytop/sweep.hpp"
#include "sweep_distribution.hpp"

namespace heavytop::cli {
namespace {

struct SweepSettings {
  std::vector<std::string> vary;
  std::string model;
  std::string integrator = "auto";
  bool tolerance_column = false;  // --tolerance-column: the CSV's nonlinear_tolerance
  SweepOptions options;
};

/// Everything the rows depend on, in one line: a resumed sweep must have the same.
/// How many points each verdict column called stable, for the line the sweep ends with.
struct VerdictCounts {
  std::size_t points = 0;
  std::array<std::size_t, kLinearModels.size()> linear{};
  std::size_t lyapunov = 0, nonlinear = 0;

  void add(const std::vector<SweepVerdict>& verdicts) {
    for (const SweepVerdict& v : verdicts) {
      ++points;
      for (std::size_t m = 0; m < linear.size(); ++m) linear[m] += v.linear[m] ? 1 : 0;
      lyapunov += v.lyapunov ? 1 : 0;
      nonlinear += v.nonlinear.value_or(false) ? 1 : 0;
    }
  }
  /// "1600 points (stable: first-order 830, body-fixed 512, linearized 790, lyapunov 700)".
  std::string words(std::size_t total, std::size_t resumed, bool with_nonlinear) const {
    std::string stable;
    for (std::size_t m = 0; m < linear.size(); ++m)
      stable += fmt::format("{}{} {}", m ? ", " : "", name(kLinearModels[m]), linear[m]);
    stable += fmt::format(", lyapunov {}", lyapunov);
    if (with_nonlinear) stable += fmt::format(", nonlinear {}", nonlinear);
    return fmt::format("{} points (stable{}: {}){}", total, resumed ? " among the computed ones" : "", stable,
                       resumed ? fmt::format("; {} rows resumed from the partial file", resumed) : "");
  }
};

std::string fingerprint(const Inputs& in, const std::vector<SweepAxis>& axes, const SweepOptions& o,
                        bool tolerance_column) {
  const Body& b = in.body();
  const InitialState& s = in.state();
  // v4: the damping, the friction and the motor change verdicts too (a v3 partial left them out).
  std::string f = fmt::format("heavytop-sweep-v4 body {} {} {} {} {} {} state {} {} {} {} {} damping {} {} {} {}", b.A,
                              b.B, b.C, b.mass, b.gravity, b.length, s.spin, s.theta0, s.phi0, s.theta_rate0,
                              s.phi_rate0, b.damping.transverse, b.damping.axial, b.damping.friction, b.damping.driven);
  for (const auto& a : axes) f += fmt::format(" vary {}={}:{}:{}", a.key, a.start, a.stop, a.count);
  if (o.nonlinear)
    f += fmt::format(" nonlinear {} {} {} {} {} {}", o.horizon, o.max_tilt, o.integrator.rtol, o.integrator.atol,
                     name(o.nonlinear_integrator), o.integrator.max_steps);
  if (in.format() != "csv") f += " format " + in.format();
  if (tolerance_column) f += " tolerance-column";
  return f + "\n";
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// How a sweep's records look in FILE.partial: CSV rows (the output itself), or the packed
/// verdicts from which the HDF5 file is written at the end (fixed-size records, so a torn
/// one is seen by the size alone).
struct Journal {
  std::string head;
  bool packed = false;
  bool tolerance = false;  // CSV rows with nonlinear_tolerance

  std::string encode(const std::vector<SweepAxis>& axes, std::size_t begin, const std::vector<SweepVerdict>& v) const {
    if (!packed) return io::sweep_csv_rows(axes, begin, v, tolerance);
    std::string bytes;
    io::pack_verdicts(v, bytes);
    return bytes;
  }
  /// The number of leading records in `content` (a partial file that starts with head) that
  /// are whole and this sweep's (io::valid_journal_records: a torn record, a row off the grid,
  /// rows beyond it, zero padding end them); `content` is cut after the last of them.
  std::size_t whole_records(std::string& content, const std::vector<SweepAxis>& axes, bool nonlinear) const {
    const std::string_view records = std::string_view(content).substr(head.size());
    const std::size_t n = io::valid_journal_records(records, axes, nonlinear, packed, tolerance);
    std::size_t bytes = n * io::kPackedVerdictSize;
    if (!packed) {
      bytes = 0;
      for (std::size_t i = 0; i < n; ++i) bytes = records.find('\n', bytes) + 1;
    }
    content.resize(head.size() + bytes);
    return n;
  }
};

}  // namespace

Action add_sweep_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("sweep", "A stability map: each model's verdict over a grid of one to three parameters");
  auto inputs = std::make_shared<Inputs>(*cmd, std::vector<std::string>{"csv", "hdf5"});
  auto s = std::make_shared<SweepSettings>();
  cmd->add_option("--vary", s->vary, "KEY=START:STOP:COUNT, KEY a body key, spin, spin_rpm (rpm; the CSV keeps spin in rad/s), B/A or C/A (one to three times)")
      ->required()
      ->expected(1, static_cast<int>(kMaxSweepAxes))
      ->take_all();
  cmd->add_option("--model", s->model, "nonlinear: add the column `nonlinear`, the verdict of a simulation")
      ->check(CLI::IsMember({"nonlinear"}));
  auto* horizon = cmd->add_option("--horizon", s->options.horizon, "s, nonlinear: simulated time of each run")
                      ->default_str("100");
  auto* max_tilt = cmd->add_option("--max-tilt", s->options.max_tilt, "rad, nonlinear: a run is stable if its tilt stays below")
                       ->default_str("0.5");
  auto max_tilt_deg = std::make_shared<DegreesOption>(*cmd, max_tilt, "max_tilt", "--max-tilt-deg",
                                                      "degrees, nonlinear: the same (instead of --max-tilt)");
  // The nonlinear verdict's settings: refused without --model nonlinear, never silently ignored.
  const std::vector<const CLI::Option*> nonlinear_only = {
      horizon, max_tilt, max_tilt_deg->option(),
      cmd->add_option("--integrator", s->integrator,
                      "nonlinear: auto (batched Taylor series, the default), taylor (the same), dopri5 or dop853 "
                      "(one point at a time)")
          ->check(CLI::IsMember({"auto", "taylor", "dopri5", "dop853"}))
          ->default_str("auto"),
      cmd->add_option("--rtol", s->options.integrator.rtol, "nonlinear: relative tolerance per step")
          ->default_str(fmt::format("{:g}", s->options.integrator.rtol)),
      cmd->add_option("--atol", s->options.integrator.atol, "nonlinear: absolute tolerance per step")
          ->default_str(fmt::format("{:g}", s->options.integrator.atol)),
      cmd->add_option("--max-steps", s->options.integrator.max_steps,
                      "nonlinear: the most integration steps one point's run may take")
          ->default_str(fmt::format("{}", s->options.integrator.max_steps))
          ->check(positive_count()),
      cmd->add_flag("--tolerance-column", s->tolerance_column,
                    "nonlinear: add the column (HDF5: dataset) `nonlinear_tolerance`, the rtol that decided each "
                    "verdict (0: decided without integration, by a symmetric top's closed form or the energy and vertical "
                    "momentum's barrier)")};
  return [inputs, s, nonlinear_only, max_tilt_deg] {
    inputs->resolve();
    if (s->model != "nonlinear")
      for (const CLI::Option* o : nonlinear_only)
        if (o->count()) throw InvalidInput(o->get_name(), "sets the nonlinear verdict: add --model nonlinear");
    max_tilt_deg->apply(s->options.max_tilt);
    std::vector<SweepAxis> axes;
    for (const auto& v : s->vary) axes.push_back(parse_sweep_axis(v));
    s->options.nonlinear = s->model == "nonlinear";
    s->options.nonlinear_integrator = *integrator_from_name(s->integrator);
    validate_sweep(inputs->body(), inputs->state(), axes, s->options);
    const bool hdf5 = inputs->format() == "hdf5";
    if (hdf5 && !io::hdf5_available())
      throw InvalidInput("--format", "hdf5: this heavytop was built without HDF5 (Debian's libhdf5-dev); use csv");
    const bool tolerance = s->tolerance_column;

    const SweepDistribution& distribution = sweep_distribution();
    s->options.threads = distribution.threads();
    const std::size_t total = grid_size(axes);
    // Blocks of grid order: each computed in parallel, then appended whole. At least 128
    // nonlinear points, so that every core gets several batches of SIMD lanes (with 8 points a
    // block was one batch: one core of two busy).
    const std::size_t block = std::clamp<std::size_t>(total / 200, s->options.nonlinear ? 128 : 256, 20000);
    const ComputeBlock compute = [&](std::size_t begin, std::size_t end) {
      std::vector<SweepVerdict> v = sweep_verdicts(inputs->body(), inputs->state(), axes, s->options, begin, end);
      if (!tolerance)
        for (SweepVerdict& x : v) x.nonlinear_tolerance.reset();  // the contract's columns, journals without it
      return v;
    };
    // MPI's ranks send "the sweep's own tolerance" as a class (io::pack_verdicts): its value here.
    const auto own_tolerance = [&](std::vector<SweepVerdict>& v) {
      for (SweepVerdict& x : v)
        if (x.nonlinear_tolerance && std::isnan(*x.nonlinear_tolerance)) x.nonlinear_tolerance = s->options.integrator.rtol;
    };
    if (!distribution.writes()) {  // an MPI rank that only computes
      distribution.run(0, total, block, compute, {});
      return;
    }

    const std::string path = io::resolved(inputs->output());
    const std::string head = io::sweep_csv_header(axes, s->options.nonlinear, tolerance);
    ProgressBar progress("sweep", static_cast<double>(total));
    VerdictCounts counts;
    const auto say_what_was_written = [&](const std::string& where, std::size_t resumed) {
      std::cerr << "heavytop: sweep wrote " << counts.words(total, resumed, s->options.nonlinear) << " to " << where
                << "\n";
    };
    if (!io::is_regular_target(path)) {  // stdout, a device or a pipe: written directly
      if (hdf5) throw InvalidInput("--output", "the hdf5 format needs a regular file (HDF5 seeks): give --output FILE.h5");
      io::OutputStream out(path, "--output");
      out.write(head);
      distribution.run(0, total, block, compute, [&](std::size_t begin, std::vector<SweepVerdict> v) {
        own_tolerance(v);
        out.write(io::sweep_csv_rows(axes, begin, v, tolerance));
        counts.add(v);
        progress.update(static_cast<double>(begin + v.size()));
      });
      out.commit();
      say_what_was_written(inputs->output().empty() || inputs->output() == "-" ? "stdout" : inputs->output(), 0);
      return;
    }

    const io::OutputLock lock(path, "--output");  // one sweep per output at a time: a second is refused
    namespace fs = std::filesystem;
    const std::string partial = path + ".partial", args_file = path + ".partial.args";
    const std::string args = fingerprint(*inputs, axes, s->options, tolerance);
    const Journal journal{.head = hdf5 ? "heavytop-sweep-journal-v1 packed verdicts\n" : head, .packed = hdf5,
                          .tolerance = tolerance};
    std::size_t done = 0;
    if (fs::exists(partial) && fs::exists(args_file) && read_file(args_file) == args) {
      std::string content = read_file(partial);
      if (content.starts_with(journal.head)) {
        done = journal.whole_records(content, axes, s->options.nonlinear);
        fs::resize_file(partial, content.size());
      }
    }
    if (done == 0) {
      write_output(args_file, args);
      write_output(partial, journal.head);
    } else {
      std::cerr << fmt::format("heavytop: resuming the sweep at row {} of {} ({})\n", done + 1, total, partial);
    }
    std::FILE* out = std::fopen(partial.c_str(), "ab");
    if (!out) throw Failure(fmt::format("--output: cannot write '{}'", partial));
    distribution.run(done, total, block, compute, [&](std::size_t begin, std::vector<SweepVerdict> v) {
      own_tolerance(v);
      // Whole blocks, flushed: an interrupted sweep leaves complete records (and at most one torn).
      const std::string bytes = journal.encode(axes, begin, v);
      if (std::fwrite(bytes.data(), 1, bytes.size(), out) != bytes.size() || std::fflush(out) != 0)
        throw Failure(fmt::format("--output: cannot write '{}'", partial));
      counts.add(v);
      progress.update(static_cast<double>(begin + v.size()));
    });
    if (std::fclose(out) != 0) throw Failure(fmt::format("--output: cannot write '{}'", partial));
    if (hdf5) {
      std::ifstream records(partial, std::ios::binary);
      io::write_atomically(path, [&](const std::string& temporary) {
        io::write_map_hdf5(
            temporary, axes, s->options.nonlinear,
            [&](std::size_t begin, std::size_t end) {
              std::string bytes((end - begin) * io::kPackedVerdictSize, '\0');
              records.seekg(static_cast<std::streamoff>(journal.head.size() + begin * io::kPackedVerdictSize));
              if (!records.read(bytes.data(), static_cast<std::streamsize>(bytes.size())))
                throw Failure(fmt::format("--output: cannot read '{}'", partial));
              return io::unpack_verdicts(bytes, s->options.integrator.rtol);
            },
            "--output", tolerance);
      });
      fs::remove(partial);
    } else {
      io::copy_mode(path, partial);
      if (std::rename(partial.c_str(), path.c_str()) != 0)
        throw Failure(fmt::format("--output: cannot replace '{}'", path));
    }
    std::error_code ignored;
    fs::remove(args_file, ignored);
    say_what_was_written(inputs->output(), done);
  };
}

}  // namespace heavytop::cli
