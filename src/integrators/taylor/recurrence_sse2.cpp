// The Taylor recurrences' kernel for SSE2, its products in pairs (recurrence_kernels.hpp), compiled
// without fused multiply-add or contraction (CMakeLists.txt) and called only where the
// processor runs it (recurrence_dispatch.cpp).
#define HEAVYTOP_RECURRENCE_SUFFIX sse2
#define HEAVYTOP_RECURRENCE_PAIRS 1
#define HEAVYTOP_RECURRENCE_WIDE 0
#include "integrators/taylor/recurrence_kernel.hpp"
