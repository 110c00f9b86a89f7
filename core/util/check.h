// Invariant checks for code that cannot fail (core math): PF_CHECK is always on,
// PF_DCHECK only in debug builds. A failed check prints where and aborts.
#pragma once

#include <cstdio>
#include <cstdlib>

namespace pf::detail {
[[noreturn]] inline void CheckFailed(const char* condition, const char* file, int line) {
    std::fprintf(stderr, "photonfarm: internal check failed: %s at %s:%d\n", condition, file, line);
    std::abort();
}
}  // namespace pf::detail

#define PF_CHECK(condition)                                            \
    do {                                                               \
        if (!(condition)) [[unlikely]]                                 \
            ::pf::detail::CheckFailed(#condition, __FILE__, __LINE__); \
    } while (false)

#ifdef NDEBUG
#define PF_DCHECK(condition) \
    do {                     \
    } while (false && (condition))
#else
#define PF_DCHECK(condition) PF_CHECK(condition)
#endif
