// Long computations run with the GIL released and stop on Ctrl-C (a Jupyter interrupt):
// the core's progress callback, or the thread that waits for the workers, polls Python's
// signals at most every 0.1 s and unwinds with Interrupted, which becomes KeyboardInterrupt.
#pragma once

#include <cstddef>
#include <functional>

#include <pybind11/pybind11.h>

namespace heavytop::python {

/// Thrown (not a std::exception, so nothing in the core catches it: simulate() turns
/// std::runtime_error into a failed summary) when Python has a pending signal; Python's error
/// indicator is then set.
struct Interrupted {};

/// True if Python has a pending signal (its error indicator is then set). Takes the GIL
/// briefly; call it with the GIL released.
bool signalled();

/// A progress callback for a core run (heavytop::Progress, an argument of simulate, compare_models, lifetime)
/// that polls Python's signals at most every 0.1 s and throws Interrupted on one.
std::function<void(double)> poll_signals();

/// Runs `compute` with the GIL released; an interruption becomes the pending Python error
/// (KeyboardInterrupt from Ctrl-C).
template <class Compute>
auto without_gil(Compute&& compute) {
  try {
    const pybind11::gil_scoped_release unlocked;
    return compute();
  } catch (const Interrupted&) {
    throw pybind11::error_already_set();
  }
}

/// f(begin, end) over [0, count) in blocks of `block`, handed out from an atomic counter to
/// one worker per core (as the core's sweep does). The calling thread (the GIL released)
/// polls Python's signals meanwhile: on one the workers stop at their next block and
/// Interrupted is thrown. Otherwise rethrows the first failure once every worker has ended.
void parallel_blocks(std::size_t count, std::size_t block, const std::function<void(std::size_t, std::size_t)>& f);

}  // namespace heavytop::python
