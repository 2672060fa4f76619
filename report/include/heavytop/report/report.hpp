#pragma once
/// \file
/// The report: one folder a person can open from disk (report.html, its figures as PNG and
/// SVG drawn by gnuplot, the data behind them as CSV and JSON, and, when the build had npm,
/// the interactive page's script heavytop-report.js with its data report-data.js); nothing is
/// fetched from a network (SPEC section 5).

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "heavytop/body.hpp"
#include "heavytop/mass_properties.hpp"
#include "heavytop/progress.hpp"
#include "heavytop/state.hpp"
#include "heavytop/sweep.hpp"
#include "heavytop/table.hpp"

namespace heavytop::report {

/// A stability map (a sweep's file) for the report to draw: a map of two keys whole, a map of
/// three as heat maps at chosen values of one key.
struct ReportMap {
  std::string file;            ///< where it was read from, as the reader gave it (shown)
  StabilityMap map;            ///< two or three keys
  std::string held;            ///< three keys: the key each slice holds (default: the last)
  std::vector<double> values;  ///< ... at its grid values nearest these (default: first, middle, last)

  /// The maps to draw, each with its words ("at C/A = 2"): the map itself, or its slices.
  /// Throws InvalidInput (key "map" or "slice") if the map has one key, `held` is not a key of
  /// it, or slices are asked of a two-key map.
  std::vector<std::pair<std::string, StabilityMap>> heat_maps() const;
};

/// One part of a body given by its parts (SPEC section 10), as the report's 3D view draws it:
/// a solid of revolution on the spin axis at its place, or a mesh from its own triangles (the
/// file's bytes go into the page, which parses them with three.js's STL, OBJ or PLY loader).
struct DrawnPart {
  std::string label;               ///< as messages name it: its shape, or a mesh's file as written
  std::optional<SolidPart> solid;  ///< a solid of revolution; nullopt for a mesh
  std::string mesh_file;           ///< a mesh: its file (a relative path already resolved)
  double scale = 1.0;              ///< a mesh: m per unit of the file
};

/// The largest mesh file the page carries (bytes): above it, the page draws that part as its
/// bounding box (a page of 100 MB of base64 would not open).
inline constexpr unsigned long long kMaxDrawnMeshBytes = 48ull << 20;

/// Writes the report for `body` and `state` into folder `dir` (created if needed): the answer
/// first (SPEC section 14, as `stability` gives it; for a damped body with its lifetime), then
/// the 3D view, the models, the motion over `t_end` (s; default: up to the fall and a fifth
/// more when the body falls, else natural_horizon()), and, if given, the heat maps of `map`.
/// `source` (the configuration file, "" for the built-in example) is named in the title.
/// `parts`, the body's parts when it was given by them: the 3D view draws those (else the
/// uniform ellipsoid with the body's mass and moments). Throws
/// InvalidInput (key "map" or "slice", before anything is made: ReportMap::heat_maps()) for a
/// map it cannot draw, InvalidInput (key "--output") if the folder cannot be made, io::Failure
/// if a figure cannot be drawn. `progress` (progress.hpp) is given to every run it makes (the
/// answer's, the models' comparison, the stability diagram's between blocks of its grid, the
/// wander's, the lifetime's); what it throws passes through, leaving the folder as it was.
void write_report(const std::string& dir, const Body& body, const InitialState& state, std::optional<double> t_end,
                  const std::optional<ReportMap>& map = std::nullopt, const std::string& source = "",
                  const std::vector<DrawnPart>& parts = {}, const Progress& progress = {});

/// Writes the report for `body` on `table` (SPEC section 16; not the pivot) started at `state`
/// into folder `dir`, as write_report() does for a pivot: the answer on the table first (io's
/// table_answer_text, from analyse_top_on_table), the 3D view (the table, the body moving across
/// it, the track of the contact point P), the tilt against time and P's track seen from above
/// (figures "tilt" and "track"), the spinning states' stability, and the data (stability.json as
/// `stability --format json`, trajectories.csv as `simulate` on the table). The motion shown is
/// one run of simulate_on_table over `t_end` (s; default: twice the answer's event, the turn-over,
/// the rise to sleep, a fall or leaving the table, else the answer's horizon). Throws as
/// write_report() does, and std::runtime_error for a failed run.
void write_table_report(const std::string& dir, const Body& body, const Table& table, const InitialState& state,
                        std::optional<double> t_end, const std::string& source = "",
                        const std::vector<DrawnPart>& parts = {});

/// What the report's 3D view draws, as the JSON text of an object (the part of report-data.js's
/// window.HEAVYTOP_REPORT that report/web/src/main.js's view reads): `body` (its moments, kg m^2,
/// mass kg, length m, gravity m/s^2), `t` (s) and `nonlinear` {theta, phi, psi} (rad) at the
/// samples shown of the run `nonlinear` of `body` (columns of simulate_nonlinear, with
/// axial_momentum), `shape` (the equivalent ellipsoid, m), `parts` (as write_report draws them;
/// a mesh's file is read), `playback` and no `models`. The explorer page (web/) draws its own
/// runs with it. Throws InvalidInput ("trajectory") without the axial_momentum column.
std::string view_data(const Body& body, const Trajectory& nonlinear, const std::vector<DrawnPart>& parts = {});

/// The explorer page (SPEC section 15; built by web/, the CMake target heavytop_web), its inputs
/// starting at `body` and `state`: the file `heavytop explore` writes and every report carries as
/// explore.html. Looked for beside the running program (build/web/), where the build made it and
/// where it is installed (share/heavytop/); nullopt when this heavytop was built without it.
/// `shared_view`: the page loads the 3D view's script from heavytop-report.js beside it (a
/// report's copy) instead of carrying its own. Throws io::Failure if a file found there is not
/// the page.
std::optional<std::string> explorer_page(const Body& body, const InitialState& state, bool shared_view = false);

}  // namespace heavytop::report
