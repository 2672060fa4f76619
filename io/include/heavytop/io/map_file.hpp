#pragma once
/// \file
/// Stability maps on disk: the sweep's CSV (SPEC section 5) and its columnar binary form,
/// HDF5 (docs/sweeps.md, "Big maps"), read back by the report and Python; and the packed
/// binary form of verdicts that a sweep's journal and its MPI messages carry.
#include <cstddef>
#include <limits>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "heavytop/sweep.hpp"

namespace heavytop::io {

/// Bytes of one grid point's verdicts in packed form: the three linear verdicts, the
/// Lyapunov verdict, its certificate, and the nonlinear verdict (0, 1, or 2 for none) in the
/// last byte's two low bits, the tolerance that decided it above them (0 none, 1 the closed
/// form, 2 kLooseTolerance, 3 the sweep's own: what MPI's ranks send; a journal has none).
inline constexpr std::size_t kPackedVerdictSize = 6;

/// Appends the packed form of `verdicts` to `out`.
void pack_verdicts(const std::vector<SweepVerdict>& verdicts, std::string& out);

/// The verdicts packed in `bytes` (a whole number of records), a nonlinear tolerance "the
/// sweep's own" as `sweep_rtol` (NaN unless given). Throws Failure if a byte is out of range or the size is not a
/// multiple of kPackedVerdictSize.
std::vector<SweepVerdict> unpack_verdicts(std::string_view bytes,
                                         double sweep_rtol = std::numeric_limits<double>::quiet_NaN());

/// How many leading records of a sweep's journal (`records`: its file after the head) are
/// this sweep's, at most grid_size(axes): CSV rows (`packed` false) byte for byte as the sweep
/// writes them at their grid point (the varied values exactly, each verdict 0 or 1, a
/// certificate of SPEC section 7 that agrees with the Lyapunov verdict, the nonlinear column
/// when `nonlinear`), or packed records in range and as consistent (the nonlinear byte 2
/// exactly when not `nonlinear`; tolerance bits exactly with `tolerance` and a verdict); CSV
/// rows with `tolerance` also have the `nonlinear_tolerance` cell, a number. A resumed sweep keeps these and computes the rest: a row off
/// the grid, rows beyond it, a crash's zero padding are never copied into the map.
std::size_t valid_journal_records(std::string_view records, const std::vector<SweepAxis>& axes, bool nonlinear,
                                  bool packed, bool tolerance = false);

/// True if this build writes and reads HDF5 maps (it found libhdf5).
bool hdf5_available();

/// The verdicts of grid points [begin, end), in grid order (a source that fills a map file).
using VerdictSource = std::function<std::vector<SweepVerdict>(std::size_t begin, std::size_t end)>;

/// Writes the map of `axes` (grid_size(axes) points, their verdicts read from `source` in
/// blocks, so a map of 10^8 points never sits in memory) to the HDF5 file `path`, created or
/// truncated (callers write to a temporary name and rename). The layout, for h5py and any
/// HDF5 reader: one 1-D dataset per varied key, `/axes/0`, `/axes/1`, ... (float64, the key's
/// grid values; attributes `key`, `start`, `stop`, `count`), and one dataset per verdict
/// column of the CSV, named as its header names it (`first-order`, `body-fixed`, `linearized`,
/// `lyapunov`, `nonlinear`: uint8 0/1; `lyapunov_certificate`: an HDF5 enumeration of SPEC
/// section 7's names), each of the grid's shape (row-major, the first key slowest), chunked
/// and compressed. The file records no times, so the same map gives the same bytes. Throws
/// Failure (naming `key`) if it cannot be written; InvalidInput(key) without HDF5.
/// With `tolerance` (sweep --tolerance-column) also `/nonlinear_tolerance`, float64: the rtol
/// that decided each nonlinear verdict (0 for the closed form).
void write_map_hdf5(const std::string& path, const std::vector<SweepAxis>& axes, bool nonlinear,
                    const VerdictSource& source, const std::string& key = "--output", bool tolerance = false);

/// Reads a map written by `heavytop sweep`, CSV or HDF5 (told apart by the file's first
/// bytes). A CSV's grid is recovered from its rows, which must be a START:STOP:COUNT grid of
/// one to three keys in grid order. Throws InvalidInput(key, rule) naming the row or dataset
/// that breaks the format.
StabilityMap read_map(const std::string& path, const std::string& key = "map");

}  // namespace heavytop::io
