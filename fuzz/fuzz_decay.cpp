// libFuzzer target: the spin-decay CSV of `heavytop fit-decay` (io::parse_decay_csv) on
// arbitrary bytes, and the fit of what it accepts when it is small (the fit is the costly
// part; a few points keep the run fast). Allowed: heavytop::InvalidInput (key "data", one
// line); anything else is a finding, as is a non-finite number in an accepted fit's result
// where the JSON would write null (issue 30: "residual RMS inf" near 1e300).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "heavytop/body.hpp"
#include "heavytop/fit_decay.hpp"
#include "heavytop/io/decay_data.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  heavytop::DecayData decay;
  try {
    decay = heavytop::io::parse_decay_csv(text, 3);
  } catch (const heavytop::InvalidInput& e) {
    if (e.key() != "data" || e.rule().find_first_of("\n\r") != std::string::npos) {
      std::fprintf(stderr, "fuzz_decay: '%s: %s'\n", e.key().c_str(), e.rule().c_str());
      std::abort();
    }
    return 0;
  }
  for (std::size_t i = 0; i < decay.t.size(); ++i)
    if (!std::isfinite(decay.t[i]) || !std::isfinite(decay.spin[i]) || decay.spin[i] < 0) std::abort();
  if (decay.t.size() > 12) return 0;
  try {
    const heavytop::DecayFit fit = heavytop::fit_spin_decay(heavytop::example_toy_top(), decay);
    if (std::isinf(fit.rms_residual) && fit.summary.converged) {
      std::fprintf(stderr, "fuzz_decay: a converged fit with an infinite residual\n");
      std::abort();
    }
  } catch (const heavytop::InvalidInput&) {
  }
  return 0;
}
