/// \file huge_pages.h
/// \brief Memory for the octree build's large arrays (corners, references, children's lists,
/// the triangle store) on transparent huge pages where the system offers them.
#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>

namespace nori {

/// \brief \p bytes of uninitialised memory, released by releaseLarge(). From 16 MiB on, the
/// block is aligned to 2 MiB and advised as a candidate for transparent huge pages (Linux
/// madvise(MADV_HUGEPAGE)): the build writes each such array once, front to back, and with
/// 4 KiB pages the first touch of every page was a page fault, about a fifth of the thread CPU
/// time of a million-triangle build. Throws std::bad_alloc when out of memory.
void *allocateLarge(size_t bytes);
/// \brief Release a block of allocateLarge() (null: nothing).
void releaseLarge(void *p) noexcept;

/// \brief std::allocator's interface over allocateLarge(); \p Init false leaves the elements
/// of resize() uninitialised (for arrays that are written in full before being read).
template <typename T, bool Init = true> struct HugePageAllocator {
    using value_type = T;
    template <typename U> struct rebind {
        using other = HugePageAllocator<U, Init>;
    };
    HugePageAllocator() = default;
    template <typename U> HugePageAllocator(const HugePageAllocator<U, Init> &) {}
    T *allocate(size_t n) {
        if (n > size_t(-1) / sizeof(T)) throw std::bad_alloc();
        return static_cast<T *>(allocateLarge(n * sizeof(T)));
    }
    void deallocate(T *p, size_t) noexcept { releaseLarge(p); }
    template <typename U, typename... Args> void construct(U *p, Args &&...args) {
        if constexpr (sizeof...(Args) == 0 && !Init) ::new (static_cast<void *>(p)) U;
        else ::new (static_cast<void *>(p)) U(std::forward<Args>(args)...);
    }
    template <typename U> bool operator==(const HugePageAllocator<U, Init> &) const { return true; }
    template <typename U> bool operator!=(const HugePageAllocator<U, Init> &) const { return false; }
};

/// \brief Deleter for arrays of allocateLarge() (trivially destructible elements).
struct LargeDeleter {
    void operator()(void *p) const noexcept { releaseLarge(p); }
};
/// \brief An array of \p n uninitialised trivially constructible elements from allocateLarge().
template <typename T> using LargeArray = std::unique_ptr<T[], LargeDeleter>;
template <typename T> LargeArray<T> makeLargeArray(size_t n) {
    static_assert(std::is_trivially_default_constructible_v<T> && std::is_trivially_destructible_v<T>);
    if (n > size_t(-1) / sizeof(T)) throw std::bad_alloc();
    return LargeArray<T>(static_cast<T *>(allocateLarge(n * sizeof(T))));
}

} // namespace nori
