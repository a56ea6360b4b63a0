/// \file test_stack_arena.cpp
/// \brief StackArena, the octree build's per-thread list memory: lists are disjoint and hold
/// what was written while later ones come and go, release() gives back exactly what followed
/// its mark, and under AddressSanitizer what is not handed out is poisoned (an overrun of one
/// list into the next is reported, as it would be with malloc).
#include <gtest/gtest.h>
#include "accel/stack_arena.h"
#include <cstddef>
#include <cstdint>
#include <vector>

using namespace nori::octree_build;

TEST(StackArena, NestedListsAreDisjointAndKeepTheirContents) {
    StackArena arena;
    const StackArena::Mark outer = arena.mark();
    // A parent's list, then children's lists that outgrow the first block (new blocks).
    uint32_t *parent = arena.allocate<uint32_t>(1000);
    for (uint32_t i = 0; i < 1000; ++i) parent[i] = i * 7u;
    for (int round = 0; round < 3; ++round) {
        const StackArena::Mark m = arena.mark();
        std::vector<uint32_t *> lists;
        for (size_t n : {size_t(10), size_t(300000), size_t(5), size_t(700000)}) {
            uint32_t *l = arena.allocate<uint32_t>(n);
            ASSERT_EQ(reinterpret_cast<uintptr_t>(l) % alignof(std::max_align_t), 0u);
            for (size_t i = 0; i < n; ++i) l[i] = uint32_t(n + i);
            lists.push_back(l);
        }
        size_t k = 0, wrong = 0;
        for (size_t n : {size_t(10), size_t(300000), size_t(5), size_t(700000)}) {
            for (size_t i = 0; i < n; ++i) wrong += lists[k][i] != uint32_t(n + i);
            ++k;
        }
        EXPECT_EQ(wrong, 0u) << "round " << round;
        arena.release(m);
        // What followed the mark is handed out again from the same place.
        uint32_t *again = arena.allocate<uint32_t>(10);
        EXPECT_EQ(again, lists[0]) << "round " << round;
        arena.release(m);
    }
    size_t wrong = 0;
    for (uint32_t i = 0; i < 1000; ++i) wrong += parent[i] != i * 7u;
    EXPECT_EQ(wrong, 0u);
    arena.release(outer);
}

#ifdef NORI_ARENA_ASAN
TEST(StackArena, WhatIsNotHandedOutIsPoisonedUnderAsan) {
    StackArena arena;
    const StackArena::Mark m = arena.mark();
    char *a = arena.allocate<char>(10);
    char *b = arena.allocate<char>(100);
    EXPECT_FALSE(__asan_address_is_poisoned(a));
    EXPECT_FALSE(__asan_address_is_poisoned(a + 9));
    EXPECT_TRUE(__asan_address_is_poisoned(a + 10));  // past the list, before the next one
    EXPECT_FALSE(__asan_address_is_poisoned(b + 99));
    EXPECT_TRUE(__asan_address_is_poisoned(b + 100));
    arena.release(m);
    EXPECT_TRUE(__asan_address_is_poisoned(a));  // released: a use after release is reported
    EXPECT_TRUE(__asan_address_is_poisoned(b + 50));
}
#else
TEST(StackArena, WhatIsNotHandedOutIsPoisonedUnderAsan) {
    GTEST_SKIP() << "not an AddressSanitizer build";
}
#endif
