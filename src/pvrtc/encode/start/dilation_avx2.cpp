// The row kernels of the intensity dilation (dilation_kernels.h) over the SIMD wrapper's 8-lane
// types (core/simd_avx2.h): the kernels written once in dilation_rows.h, which dilation.cpp
// compiles over the 4-lane types, here with 32 texels per step; bit-identical to them. This file
// alone is compiled with -mavx2 (src/CMakeLists.txt: every */*_avx2.cpp, with
// TESSERA_HAVE_AVX2_KERNELS defined for the library), which gives the wrapper its AVX2 backend,
// and dilation.cpp calls it only on CPUs with AVX2. Compiled without -mavx2 it is empty.
//
// ODR safety: an inline function or template with external linkage compiled here could be the
// copy the linker keeps for the whole program, and then run on a CPU without AVX2. The wrapper's
// functions compiled here live in their own inline namespace (simd_select.h); otherwise this file
// includes only C headers, dilation_kernels.h (plain declarations) and dilation_rows.h (templates
// with internal linkage), and exports one function that fills the kernel table.
#include "pvrtc/encode/start/dilation_kernels.h"

#if defined(TESSERA_HAVE_AVX2_KERNELS) && !defined(__AVX2__)
#error "dilation_avx2.cpp must be compiled with -mavx2 where TESSERA_HAVE_AVX2_KERNELS is set"
#endif

#if defined(__AVX2__)

#include "core/simd.h"
#include "pvrtc/encode/start/dilation_rows.h"

namespace tessera::pvrtc::detail {

void fill_dilation_kernels_avx2(DilationKernels* k) {
  *k = RowKernels<simd::vf32x8, simd::vu8x32>::kTable;
}

}  // namespace tessera::pvrtc::detail

#endif  // __AVX2__
