/// \file test_huge_pages.cpp
/// \brief allocateLarge() and HugePageAllocator: blocks below and above the huge-page size are
/// usable in full, large ones start on a 2 MiB boundary, and a store built through them holds
/// what was written.
#include <gtest/gtest.h>
#include "accel/huge_pages.h"
#include <cstdint>
#include <vector>

using namespace nori;

TEST(HugePages, BlocksOfEverySizeAreUsableInFull) {
    for (size_t bytes : {size_t(0), size_t(1), size_t(4095), size_t(1) << 21, (size_t(16) << 20) - 1, size_t(16) << 20,
                         (size_t(40) << 20) + 12345}) {
        LargeArray<uint32_t> a = makeLargeArray<uint32_t>(bytes / 4);
        ASSERT_NE(a.get(), nullptr) << bytes;
        for (size_t i = 0; i < bytes / 4; ++i) a[i] = uint32_t(i * 2654435761u);
        size_t wrong = 0;
        for (size_t i = 0; i < bytes / 4; ++i) wrong += a[i] != uint32_t(i * 2654435761u);
        EXPECT_EQ(wrong, 0u) << bytes;
        // From 16 MiB on the block is aligned to the huge page (else the advice could not
        // cover its first pages).
        if (bytes >= (size_t(16) << 20)) {
            EXPECT_EQ(reinterpret_cast<uintptr_t>(a.get()) % (size_t(1) << 21), 0u) << bytes;
        }
    }
}

TEST(HugePages, AllocatorBehavesAsAVectorsAllocator) {
    // Initialised elements (the default) are value-initialised by resize(), as with std::allocator.
    std::vector<float, HugePageAllocator<float>> v(size_t(5) << 20, 1.5f);
    v.resize(v.size() + 1000);
    EXPECT_EQ(v[0], 1.5f);
    EXPECT_EQ(v[(size_t(5) << 20) - 1], 1.5f);
    EXPECT_EQ(v.back(), 0.0f);
    std::vector<float, HugePageAllocator<float>> w = v;  // copy through the allocator
    EXPECT_EQ(w.size(), v.size());
    EXPECT_EQ(w[12345], 1.5f);
    std::vector<int, HugePageAllocator<int, false>> u;
    u.push_back(7);
    u.resize(100);  // (elements 1..99 uninitialised: not read)
    EXPECT_EQ(u[0], 7);
    EXPECT_EQ(u.size(), 100u);
}
