// The Taylor recurrences' outer-product kernel for AVX512 (recurrence_kernels.hpp), compiled
// without fused multiply-add or contraction (CMakeLists.txt) and called only where the
// processor runs it (recurrence_dispatch.cpp).
#define HEAVYTOP_RECURRENCE_SUFFIX avx512
#define HEAVYTOP_RECURRENCE_PAIRS 0
#define HEAVYTOP_RECURRENCE_WIDE 1
#include "integrators/taylor/recurrence_kernel.hpp"
