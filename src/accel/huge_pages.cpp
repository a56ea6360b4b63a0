/// \file huge_pages.cpp
/// \brief allocateLarge(): large blocks aligned to 2 MiB and advised for transparent huge pages.
#include "huge_pages.h"
#include <cstdlib>
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace nori {

namespace {
constexpr size_t kHugePage = size_t(1) << 21;  // x86-64's transparent huge page
// From this size on. glibc maps blocks above 32 MiB afresh each time and returns them at
// free(); smaller ones come from its heap, whose pages are usually still mapped from an
// earlier build (no faults at all), and advising those made some 100k-triangle builds slower
// by a third in 4 of 9 nori-bench runs (likely fresh huge pages zeroed where 4 KiB pages were
// reused). At 16 MiB a million-triangle build loses all but 80 of its 36,000 faults (corners,
// references, the root's lists, the store).
constexpr size_t kLarge = size_t(16) << 20;
} // namespace

void *allocateLarge(size_t bytes) {
    void *p = nullptr;
    if (bytes >= kLarge && bytes <= size_t(-1) - kHugePage) {
        // Whole huge pages: the advice applies to ranges, and a block sharing its last huge
        // page with other data could not be backed by one.
        const size_t rounded = (bytes + kHugePage - 1) & ~(kHugePage - 1);
        p = std::aligned_alloc(kHugePage, rounded);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
        // Only advice: where huge pages are off (or the call fails) the block keeps small pages.
        if (p) (void)madvise(p, rounded, MADV_HUGEPAGE);
#endif
    } else {
        p = std::malloc(bytes ? bytes : 1);
    }
    if (!p) throw std::bad_alloc();
    return p;
}

void releaseLarge(void *p) noexcept { std::free(p); }

} // namespace nori
