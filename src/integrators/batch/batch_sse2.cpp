// The batch kernel for the x86-64 baseline (SSE2, 2 lanes), compiled with -ffp-contract=off
// like the others (CMakeLists.txt).
#define HEAVYTOP_BATCH_NS sse2
#define HEAVYTOP_BATCH_LANES 2
#define HEAVYTOP_BATCH_ENTRY batch_scan_sse2
#include "integrators/batch/batch_kernel.hpp"
