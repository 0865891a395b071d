// The portable build of the inner loops (kernels_impl.h): compiled with the project's default
// flags, so it runs on any CPU the rest of the program runs on (four SSE2 lanes on x86-64).
#define GRADER_KERNELS_NAMESPACE portable
#define GRADER_KERNELS_NAME "portable"
#include "kernels_impl.h"
