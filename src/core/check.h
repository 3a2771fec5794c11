// check.h — internal invariant checks (pbrt-v4's util/check.h habit).
//
// `TESSERA_DCHECK(cond)` states an invariant of the code itself (an index inside its array, a
// value inside its range), never a property of user input: input errors are reported through
// `Status`. It is checked where `NDEBUG` is not defined (debug builds) or where
// `TESSERA_ENABLE_DCHECKS` is defined (the sanitizer build: src/CMakeLists.txt defines it with
// `TESSERA_SANITIZE`); a failure prints file:line and the condition to stderr and aborts.
// Elsewhere (Release) it compiles to nothing and does not evaluate `cond`, so it may sit in
// kernels, though not in the innermost per-texel loops.
#pragma once

#if !defined(NDEBUG) || defined(TESSERA_ENABLE_DCHECKS)
#define TESSERA_DCHECKS_ENABLED 1
#else
#define TESSERA_DCHECKS_ENABLED 0
#endif

namespace tessera::detail {

/// Prints "file:line: TESSERA_DCHECK(condition) failed" to stderr and aborts.
[[noreturn]] void dcheck_failed(const char* file, int line, const char* condition) noexcept;

}  // namespace tessera::detail

#if TESSERA_DCHECKS_ENABLED
#define TESSERA_DCHECK(cond) \
  ((cond) ? static_cast<void>(0) : ::tessera::detail::dcheck_failed(__FILE__, __LINE__, #cond))
#else
// Not evaluated; sizeof keeps the expression type-checked (and its variables "used").
#define TESSERA_DCHECK(cond) static_cast<void>(sizeof(static_cast<bool>(cond)))
#endif
