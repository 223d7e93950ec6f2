// MESHIK_SIMD_CLONES marks a hot loop function to be compiled for AVX-512, AVX2+FMA and the
// baseline instruction set, the best one being chosen at load time (GCC function multiversioning),
// so the library stays portable while its batch loops use the machine's full vector width.
#pragma once

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define MESHIK_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define MESHIK_SIMD_CLONES
#endif
