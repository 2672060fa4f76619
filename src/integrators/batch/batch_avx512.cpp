// The batch kernel for AVX-512F (8 lanes), compiled with -mavx512f -mno-fma
// -ffp-contract=off (CMakeLists.txt) and called only where the processor has AVX-512F (batch.cpp).
#define HEAVYTOP_BATCH_NS avx512
#define HEAVYTOP_BATCH_LANES 8
#define HEAVYTOP_BATCH_ENTRY batch_scan_avx512
#include "integrators/batch/batch_kernel.hpp"
