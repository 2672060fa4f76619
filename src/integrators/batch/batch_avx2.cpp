// The batch kernel for AVX2 (4 lanes), compiled with -mavx2 -mno-fma -ffp-contract=off
// (CMakeLists.txt) and called only where the processor has AVX2 (batch.cpp).
#define HEAVYTOP_BATCH_NS avx2
#define HEAVYTOP_BATCH_LANES 4
#define HEAVYTOP_BATCH_ENTRY batch_scan_avx2
#include "integrators/batch/batch_kernel.hpp"
