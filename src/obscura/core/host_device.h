#pragma once
// Functions that the CPU and a CUDA device both run (pbrt-v4's PBRT_CPU_GPU):
// the lattice march, the cell quadrature, the Planck table's lookup, the DDA
// (docs/gpu.md). nvcc compiles them for both sides; every other compiler sees
// ordinary inline functions, so a build without CUDA is unchanged.
// OBSCURA_DEVICE_CODE is true only in nvcc's device pass, for the few places
// where the two sides read memory differently (16-byte vector loads).
#if defined(__CUDACC__)
#define OBSCURA_HOST_DEVICE __host__ __device__
#else
#define OBSCURA_HOST_DEVICE
#endif

#if defined(__CUDA_ARCH__)
#define OBSCURA_DEVICE_CODE 1
#else
#define OBSCURA_DEVICE_CODE 0
#endif

// Inlined whatever the compiler's heuristics say (GCC, Clang and nvcc): for
// the lattice march's cell walk and its callbacks, whose state must stay in
// registers (a call left in place cost the CPU march 12 %, measured).
#define OBSCURA_ALWAYS_INLINE __attribute__((always_inline))

// Every call in the function inlined, recursively (GCC and Clang; nvcc
// inlines a device function's calls anyway): for the CPU's lattice march,
// whose inlining the heuristics otherwise decide by the size of the whole
// program, so that adding code elsewhere can leave its small callees as
// calls (docs/performance.md).
#if defined(__CUDACC__)
#define OBSCURA_FLATTEN
#else
#define OBSCURA_FLATTEN __attribute__((flatten))
#endif
