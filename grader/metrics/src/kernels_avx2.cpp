// The AVX2 + FMA build of the inner loops (kernels_impl.h). CMake compiles this file alone
// with -mavx2 -mfma on x86-64 and defines GRADER_HAVE_AVX2_KERNELS for the dispatcher
// (kernels.cpp), which calls it only when the CPU and OS support AVX2 and FMA. Elsewhere the
// file compiles to nothing.
#if defined(__AVX2__) && defined(__FMA__)
#define GRADER_KERNELS_NAMESPACE avx2
#define GRADER_KERNELS_NAME "avx2-fma"
#include "kernels_impl.h"
#endif
