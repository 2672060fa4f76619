// The docstrings of heavytop._core. The public functions (heavytop.stability, simulate,
// compare, sweep, derive*) are documented in heavytop/_api.py, which wraps these; the classes
// and functions heavytop re-exports unchanged (Body, InvalidInput, example_*, grid_values)
// are documented here.
#pragma once

namespace heavytop::python::docs {

constexpr const char* kCoreModule = R"doc(heavytop._core: the compiled bindings of the heavytop package (pybind11, NumPy).

Use the package instead: `import heavytop`. The functions here take every argument explicitly
and return raw data (JSON objects as dicts, NumPy columns); heavytop's functions give them
their defaults and wrap what they return in typed results (heavytop.results).
)doc";

constexpr const char* kInvalidInput =
    "Bad input: a ValueError whose message is '<key>: <rule>', the key being the keyword argument's "
    "name (rtol, max_tilt, samples, t_end, vary, ...) or the configuration file's key for the body and "
    "the motion (body.A, motion.spin); the attributes key and rule hold the two parts.";

constexpr const char* kBody = R"doc(A rigid body turning about a fixed point O in uniform gravity (SPEC section 1). Immutable.

    Body(A, B, C, mass, length, gravity=9.81, *, transverse_damping=0.0, axial_damping=0.0,
         friction=0.0, driven=False, offset_x=0.0, offset_y=0.0, Ixy=0.0, Ixz=0.0, Iyz=0.0,
         tip_radius=0.0, rim_radius=0.0)

A, B, C (kg m^2): principal moments of inertia about the body axes x, y, z through O; mass (kg);
length (m): R, signed distance from O to the centre of mass along z (> 0: a top on its tip,
< 0: a hanging gyroscope); gravity (m/s^2): g, acting along -zeta. mgR (N m): m g R.
The keywords, each 0 (False) by default and described in Body.__init__ (help(heavytop.Body)):
  damping (SPEC section 6):     transverse_damping, axial_damping (N m s), friction (N m), driven
  a general body (section 11):  offset_x, offset_y (m), Ixy, Ixz, Iyz (kg m^2)
  on a table (section 16):      tip_radius, rim_radius (m)

Body frame: principal axes x, y, z through O, z the spin (symmetry) axis. Validated exactly as
the command line validates [body]: A, B, C, mass finite and > 0, gravity finite and >= 0,
length finite, and A + B >= C, B + C >= A, C + A >= B; else InvalidInput (a ValueError),
e.g. "body.mass: must be > 0".
)doc";

constexpr const char* kBodyInit = R"doc(A, B: kg m^2, moments of inertia about the body's transverse axes x, y through O
C: kg m^2, moment of inertia about the spin axis z through O
mass: kg
length: m, R: signed distance from O to the centre of mass along z (> 0: a top on its tip,
        < 0: a hanging gyroscope)
gravity: m/s^2, g (default 9.81), acting along -zeta
transverse_damping, axial_damping: N m s, d_t, d_a (>= 0, default 0): the drag torques
        -d_t w_perp and -d_a (w.k) k (SPEC section 6)
friction: N m, tau0 (>= 0, default 0): dry friction at the tip, -tau0 sign(w.k) k
driven: True: a motor holds the spin w.k at its value at t = 0 (a gyroscope))doc";

constexpr const char* kExampleToyTop =
    "The built-in example (the command line's base without --config): a wooden toy top, 60 g,\n"
    "a 40 mm disc on a spindle, the centre of mass 25 mm above the tip (SI units).";

constexpr const char* kExampleMotion =
    "The built-in example's motion as keyword arguments: spin 200 rad/s, theta0 0.05 rad, the\n"
    "rest 0. E.g. heavytop.simulate(heavytop.example_toy_top(), **heavytop.example_motion()).";

constexpr const char* kCoreLifetime = R"doc(heavytop.lifetime without defaults: json.loads of `heavytop lifetime --format json`.
)doc";

constexpr const char* kGridValues = R"doc(The values of the command line's --vary KEY=START:STOP:COUNT, bit for bit:
start + i (stop - start) / (count - 1), i = 0..count-1 (float64 array, in the key's SI unit:
rad/s for spin, kg m^2 for A, B, C, kg for mass, m for length, m/s^2 for gravity). Pass them to sweep()
to reproduce a command-line sweep exactly. start, stop finite; count an integer in
[1, 100000000] (else InvalidInput, e.g. "count: must be an integer in [1, 100000000]").
)doc";

constexpr const char* kCoreSimulate = R"doc(heavytop.simulate without defaults: every model through the core's heavytop::simulate().

Returns (columns, summary): a dict of float64 arrays, one per CSV column, and the
SimulationSummary as a dict (termination "success" | "failure" and its message; a failed run
is reported there, not raised). heavytop.simulate() raises RuntimeError on a failure instead.
)doc";

constexpr const char* kCoreStability =
    "heavytop.stability as json.loads of `heavytop stability --format json` (a dict).";

constexpr const char* kCoreCompare =
    "heavytop.compare without defaults, as json.loads of `heavytop compare --format json` (a dict).";

constexpr const char* kCoreReadMap = R"doc(The columns and grid shape of a map file written by `heavytop sweep` (CSV or HDF5).

The engine behind heavytop.read_map(), which returns a StabilityMap.)doc";

constexpr const char* kCoreSweep =
    "heavytop.sweep without defaults: a dict of arrays, one per CSV column of `heavytop sweep`.";

constexpr const char* kCoreDerive =
    "heavytop.derive without defaults, as json.loads of `heavytop derive --format json` (a dict).";

constexpr const char* kCoreDeriveRotations =
    "heavytop.derive_rotations, as json.loads of `heavytop derive --rotations --format json` (a dict).";

constexpr const char* kCoreDeriveCheck =
    "heavytop.derive_check, as json.loads of `heavytop derive --check --format json` (a dict).";

}  // namespace heavytop::python::docs
