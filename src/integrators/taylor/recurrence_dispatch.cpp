// The choice of the Taylor recurrences' kernel (recurrence_kernels.hpp) at run time, as the
// batch chooses its own (batch.cpp). All give the same bits.

#include "integrators/taylor/recurrence_kernels.hpp"

#include "heavytop/taylor.hpp"

namespace heavytop::detail::taylor {

static_assert(kTaylorMaxOrder == 24, "recurrence_kernel.hpp's rows hold orders 0..24");

bool recurrence_isa_supported(int isa) {
#if defined(__x86_64__) || defined(__i386__)
  if (isa == 1) return __builtin_cpu_supports("avx2");
  if (isa == 2) return __builtin_cpu_supports("avx512f");
#else
  if (isa != 0) return false;
#endif
  return isa == 0;
}

// AVX2 where the processor has it: the AVX-512 form (two 8-wide products per j) measured
// slower here (bench_recurrence: plain p = 22 2.8 against 2.1 ns per iteration, Xeon with
// AVX-512), so it is kept for the benchmark and not chosen.
int best_recurrence_isa() {
  static const int best = recurrence_isa_supported(1) ? 1 : 0;
  return best;
}

#if defined(__x86_64__) || defined(__i386__)
PlainKernel plain_kernel(int isa) {
  return isa == 2 ? plain_coefficients_avx512 : isa == 1 ? plain_coefficients_avx2 : plain_coefficients_sse2;
}
FactoredKernel factored_kernel(int isa) {
  return isa == 2 ? factored_coefficients_avx512 : isa == 1 ? factored_coefficients_avx2 : factored_coefficients_sse2;
}
#else  // WebAssembly (web/): the portable kernel only (the others are not compiled there)
PlainKernel plain_kernel(int) { return plain_coefficients_sse2; }
FactoredKernel factored_kernel(int) { return factored_coefficients_sse2; }
#endif

PlainKernel best_plain_kernel() {
  static const PlainKernel k = plain_kernel(best_recurrence_isa());
  return k;
}
FactoredKernel best_factored_kernel() {
  static const FactoredKernel k = factored_kernel(best_recurrence_isa());
  return k;
}

}  // namespace heavytop::detail::taylor
