#pragma once
// Private to the Taylor integrator: the recurrences of the Plain and SpinFactored sets
// (recurrence.hpp) in the outer-product form, compiled once per instruction set
// (recurrence_sse2.cpp, recurrence_avx2.cpp, recurrence_avx512.cpp, each through
// recurrence_kernel.hpp) and chosen at run time (recurrence_dispatch.cpp), as the batch's
// kernels are. No heavytop header here, as in integrators/batch/batch.hpp: nothing inline
// shared with other translation units may be compiled for AVX-512.
//
// Bit-identity: every product and every sum of the recurrence is the one recurrence.hpp forms
// (the batch's rule, integrators/batch/batch_kernel.hpp): each accumulator adds its products
// from 0 in one order, j = 1..n-1, then j = 0 and j = n, no fused multiply-add
// (-ffp-contract=off, -mno-fma), the same final expressions. That order puts last the two
// products with row n, which order n - 1 has only just formed, so the rest of the sum runs
// while it is formed (bench_recurrence). Only the grouping into registers differs: the four
// quaternion components q_i times one w_m form one 4-wide product (an outer product q x w,
// three of them per j), the vertical's four products one more, the gyroscopic three one more.

namespace heavytop::detail::taylor {

// The coefficients a kernel needs (recurrence.hpp's Plain and SpinFactored hold them).
struct PlainConstants {
  double e1, e2, e3;  // (B - C)/A, (C - A)/B, (A - B)/C (dimensionless)
  double ka, kb;      // m g R / A, m g R / B (1/s^2)
};
struct FactoredConstants {
  double c_over_a;  // C / A (dimensionless)
  double ka;        // m g R / A (1/s^2)
};

// Coefficients 1..p of every variable of the jet c[0..kM][8] from row 0, and gamma's
// (g1[n], g2[n], n < p), as Plain::coefficients and SpinFactored::coefficients.
using PlainKernel = void (*)(double (*c)[8], double* g1, double* g2, int p, const PlainConstants& k);
using FactoredKernel = void (*)(double (*c)[8], double* g1, double* g2, int p, const FactoredConstants& k);

void plain_coefficients_sse2(double (*c)[8], double* g1, double* g2, int p, const PlainConstants& k);
void plain_coefficients_avx2(double (*c)[8], double* g1, double* g2, int p, const PlainConstants& k);
void plain_coefficients_avx512(double (*c)[8], double* g1, double* g2, int p, const PlainConstants& k);
void factored_coefficients_sse2(double (*c)[8], double* g1, double* g2, int p, const FactoredConstants& k);
void factored_coefficients_avx2(double (*c)[8], double* g1, double* g2, int p, const FactoredConstants& k);
void factored_coefficients_avx512(double (*c)[8], double* g1, double* g2, int p, const FactoredConstants& k);

// The instruction sets, as BatchIsa (batch.hpp): 0 SSE2, 1 AVX2, 2 AVX-512F.
int best_recurrence_isa();
bool recurrence_isa_supported(int isa);
PlainKernel plain_kernel(int isa);
FactoredKernel factored_kernel(int isa);

// best_recurrence_isa()'s, chosen once.
PlainKernel best_plain_kernel();
FactoredKernel best_factored_kernel();

}  // namespace heavytop::detail::taylor
