// The Taylor recurrences' outer-product kernel for AVX2 (recurrence_kernels.hpp), compiled
// without fused multiply-add or contraction (CMakeLists.txt) and called only where the
// processor runs it (recurrence_dispatch.cpp).
#define HEAVYTOP_RECURRENCE_SUFFIX avx2
#define HEAVYTOP_RECURRENCE_PAIRS 0
#define HEAVYTOP_RECURRENCE_WIDE 0
#include "integrators/taylor/recurrence_kernel.hpp"
