/// \file test_select_smallest.cpp
/// \brief selectSmallest() (the leaf chunk order's selection): on random, tied, sorted,
/// reversed, constant and organ-pipe keys of many sizes and every split point, the result is
/// a permutation of the input whose first k elements are the k smallest (the set
/// std::nth_element leaves there, up to ties).
#include <gtest/gtest.h>
#include "accel/select_smallest.h"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

using namespace nori;

namespace {

struct Item {
    float key;
    uint32_t id;
};

/// The key patterns: 0 random, 1 few distinct values (many ties), 2 sorted, 3 reversed,
/// 4 constant, 5 organ pipe, 6 sorted with one tie block in the middle.
std::vector<Item> makeItems(int pattern, size_t n, std::mt19937 &rng) {
    std::vector<Item> items(n);
    std::uniform_real_distribution<float> uniform(-1000.0f, 1000.0f);
    std::uniform_int_distribution<int> few(0, 3);
    for (size_t i = 0; i < n; ++i) {
        float k = 0.0f;
        switch (pattern) {
        case 0: k = uniform(rng); break;
        case 1: k = float(few(rng)); break;
        case 2: k = float(i); break;
        case 3: k = float(n - i); break;
        case 4: k = 7.5f; break;
        case 5: k = float(std::min(i, n - 1 - i)); break;
        default: k = (i > n / 3 && i < 2 * n / 3) ? float(n / 3) : float(i); break;
        }
        items[i] = {k, uint32_t(i)};
    }
    return items;
}

/// Empty when \p got is \p input rearranged with its k smallest keys first; else what is wrong.
std::string check(const std::vector<Item> &input, const std::vector<Item> &got, size_t k) {
    std::vector<uint32_t> ids;
    for (const Item &it : got) ids.push_back(it.id);
    std::sort(ids.begin(), ids.end());
    for (size_t i = 0; i < ids.size(); ++i)
        if (ids[i] != i) return "not a permutation";
    for (const Item &it : got)
        if (it.key != input[it.id].key) return "an element changed its key";
    if (k == 0 || k >= got.size()) return "";
    float below = -INFINITY, above = INFINITY;
    for (size_t i = 0; i < k; ++i) below = std::max(below, got[i].key);
    for (size_t i = k; i < got.size(); ++i) above = std::min(above, got[i].key);
    if (below > above) return "a larger key before kth than after it";
    // The same boundary as std::nth_element's.
    std::vector<Item> ref = input;
    std::nth_element(ref.begin(), ref.begin() + k, ref.end(), [](const Item &a, const Item &b) { return a.key < b.key; });
    if (ref[k].key != above) return "the key at kth differs from std::nth_element's";
    return "";
}

} // namespace

TEST(SelectSmallest, TheFirstKAreTheKSmallestOnEveryPattern) {
    std::mt19937 rng(20261123);
    size_t cases = 0;
    for (int pattern = 0; pattern <= 6; ++pattern)
        for (size_t n : {size_t(2), size_t(3), size_t(17), size_t(32), size_t(33), size_t(100), size_t(1000), size_t(4099)}) {
            const std::vector<Item> input = makeItems(pattern, n, rng);
            // Every split point for small inputs, a spread of them for large ones.
            const size_t step = n <= 100 ? 1 : n / 37;
            for (size_t k = 0; k <= n; k += step) {
                std::vector<Item> got = input;
                selectSmallest(got.data(), got.data() + k, got.data() + n, [](const Item &it) { return it.key; });
                const std::string wrong = check(input, got, k);
                ASSERT_TRUE(wrong.empty()) << wrong << " (pattern " << pattern << ", n " << n << ", k " << k << ")";
                ++cases;
            }
        }
    EXPECT_GT(cases, 1000u);
}

TEST(SelectSmallest, TheCheckRejectsAWrongSelection) {
    // The checker itself must catch a selection that is off by one element.
    std::mt19937 rng(7);
    const std::vector<Item> input = makeItems(0, 200, rng);
    std::vector<Item> got = input;
    std::nth_element(got.begin(), got.begin() + 100, got.end(), [](const Item &a, const Item &b) { return a.key < b.key; });
    EXPECT_TRUE(check(input, got, 100).empty());
    std::swap(got[0], got[150]);
    EXPECT_FALSE(check(input, got, 100).empty());
}
