// SHADERLAB_ASAN: 1 when this file is compiled with AddressSanitizer (GCC's
// __SANITIZE_ADDRESS__, clang's __has_feature(address_sanitizer); clang 14 does not define the
// former), else 0. For the few places where an ASan process must behave differently: it reserves
// terabytes of address space for its shadow memory, so it cannot live under RLIMIT_AS, and it runs
// several times slower, so tests that check time limits scale them.
#pragma once

#if defined(__SANITIZE_ADDRESS__)
#define SHADERLAB_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SHADERLAB_ASAN 1
#endif
#endif
#ifndef SHADERLAB_ASAN
#define SHADERLAB_ASAN 0
#endif
