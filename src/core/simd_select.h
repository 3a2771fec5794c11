// simd_select.h — part of the SIMD wrapper (include "core/simd.h", which documents the whole set):
// the one place the backend is chosen. The ladder below defines the backend's macros and the
// inline namespace, then includes one 4-lane backend and one 8-lane backend; no other file of
// the wrapper tests which instruction set the compiler targets. A new backend (SVE, WASM SIMD)
// is a new file beside simd_sse.h / simd_neon.h / simd_scalar.h (4 lanes) or simd_avx2.h /
// simd_halves.h (8 lanes), and a branch here.
//
// 4 lanes: SSE2 on x86-64 (part of the ABI, so always there), SSE4.1 instructions where the
// compiler targets them (simd_sse.h); NEON on little-endian AArch64 (part of its base ISA,
// simd_neon.h); otherwise (other CPUs, or TESSERA_NO_SIMD defined for every translation unit of
// the build) a portable scalar backend (simd_scalar.h). All three give bit-identical results.
// TESSERA_SIMD_VECTOR is 1 when the types map to vector registers (SSE2, NEON); kernels that
// have their own per-lane fallback (texture `sample4`, raster quad coverage) use the vector path
// only then.
//
// 8 lanes: AVX2 (simd_avx2.h) where the translation unit targets AVX2 on top of the SSE2 backend
// (the -mavx2 *_avx2.cpp kernels), and everywhere else two 4-lane halves of whatever 4-lane
// backend was chosen (simd_halves.h), which spells out lane by lane what has no 4-lane
// counterpart. Both give the same bits for every operation (tests/unit/simd_wide_test.cpp runs
// the same reference checks on each), so a kernel written over these types gives the same
// results whichever it is compiled with.
//
// TESSERA_SIMD_X86_DISPATCH: the x86 vector backend on an x86 target, where simd_dispatch.h's
// run-time CPU checks and SSSE3 routine exist.
//
// TESSERA_SIMD_ISA: the inline namespace that holds every type and function of the wrapper, one
// name per backend and per instruction set the translation unit is compiled for. The run-time
// dispatched AVX2 kernels (*_avx2.cpp, built with -mavx2) include this wrapper too: there its
// inline functions are compiled with VEX encodings, so they must not share a mangled name with
// the baseline's copies (the linker keeps one copy of an inline function for the whole program,
// and an AVX2 one must never run on a CPU without AVX2). The namespace keeps them apart; it also
// lets a TESSERA_NO_SIMD test link beside the vector backend.
#pragma once

#if !defined(TESSERA_NO_SIMD) && (defined(__SSE2__) || defined(_M_X64))
#define TESSERA_SIMD_SSE2 1
#define TESSERA_SIMD_VECTOR 1
#if defined(__SSE4_1__)
#define TESSERA_SIMD_SSE41 1
#endif
#if defined(__x86_64__) || defined(__i386__)
#define TESSERA_SIMD_X86_DISPATCH 1
#endif
#if defined(__AVX2__)
#define TESSERA_SIMD_AVX2 1
#define TESSERA_SIMD_ISA avx2
#else
#define TESSERA_SIMD_ISA sse2
#endif
#elif !defined(TESSERA_NO_SIMD) && defined(__aarch64__) && defined(__ARM_NEON) && \
    !defined(__ARM_BIG_ENDIAN)
#define TESSERA_SIMD_NEON 1
#define TESSERA_SIMD_VECTOR 1
#define TESSERA_SIMD_ISA neon
#elif defined(__AVX2__)
#define TESSERA_SIMD_VECTOR 0
#define TESSERA_SIMD_ISA scalar_avx2
#else
#define TESSERA_SIMD_VECTOR 0
#define TESSERA_SIMD_ISA scalar
#endif

// The backends, as chosen above: the 4-lane types, the compositions shared by every 4-lane
// backend, then the 8-lane types (built on the 4-lane ones).
#if defined(TESSERA_SIMD_SSE2)
#include "core/simd_sse.h"
#elif defined(TESSERA_SIMD_NEON)
#include "core/simd_neon.h"
#else
#include "core/simd_scalar.h"
#endif
#include "core/simd_compose4.h"
#if defined(TESSERA_SIMD_AVX2)
#include "core/simd_avx2.h"
#else
#include "core/simd_halves.h"
#endif
