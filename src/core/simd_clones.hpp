// FLUIDEM_SIMD_CLONES: a function so marked is compiled three times, for AVX-512, AVX2 and the
// x86-64 baseline, and the loader picks the one the processor runs (GCC function
// multiversioning; clang 14 does not multiversion templates, other architectures have their
// own baseline). A build for the build machine (FLUIDEM_NATIVE) has one path: a clone for a
// subset of -march=native cannot inline the kernels, which are compiled for all of it.
// The sanitizer build (FLUIDEM_NO_SIMD_CLONES) has the baseline only: it checks memory and
// undefined behaviour, which the clones do not change (contact_forces.cpp compiles there in
// 114 s instead of 260 s).
// The translation units that use it are compiled with -ffp-contract=off (CMakeLists.txt), so
// that the clones compute the same bits (no FMA in one clone and not in another).
#pragma once

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(FLUIDEM_NATIVE) && \
    !defined(FLUIDEM_NO_SIMD_CLONES)
#define FLUIDEM_SIMD_CLONES [[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]]
#else
#define FLUIDEM_SIMD_CLONES
#endif
