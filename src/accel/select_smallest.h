/// \file select_smallest.h
/// \brief selectSmallest(): the k smallest elements of a range first, by a quickselect whose
/// partitions do not branch on the data (for TriangleStore::setLeaf's chunk order).
#pragma once

#include <algorithm>
#include <cstddef>
#include <utility>

namespace nori {

/// \brief Rearrange [first, last) so that the elements before \p kth are the kth - first
/// smallest by \p key (a float of an element) and those from \p kth on none smaller: the set
/// std::nth_element leaves before kth, up to ties (equal keys may fall on either side), in
/// another order within the two parts. Keys must not be NaN (they then count as equal to
/// every key: the result is still a permutation, only not ordered).
///
/// Hoare's quickselect (1961) with the median of three as pivot, each partition Lomuto's
/// written without a branch on the data: every element is swapped with the first one not
/// below the pivot, and that boundary moves by the comparison's result. std::nth_element
/// branches on each comparison, which a random order mispredicts half of the time; on
/// leaves of thousands of triangles (pa5 table) the chunk order was a fifth of the build.
/// Where the pivot is the range's least key, the keys equal to it are split off in a second
/// pass, so any number of equal keys (grid-aligned scenes) still makes progress. After
/// 2 log2(n) + 8 rounds (an adversarial order) the rest goes to std::nth_element.
template <typename T, typename Key> void selectSmallest(T *first, T *kth, T *last, Key key) {
    if (kth <= first || kth >= last) return;
    size_t rounds = 8;
    for (size_t n = size_t(last - first); n > 1; n >>= 1) rounds += 2;
    // Partition [first, last) by pred (true: to the front); returns the first element of the
    // back part.
    auto partition = [&](auto pred) {
        T *front = first;
        for (T *i = first; i < last; ++i) {
            const T x = *i;
            const bool p = pred(key(x));
            *i = *front;
            *front = x;
            front += p;
        }
        return front;
    };
    while (last - first > 1) {
        if (rounds-- == 0) {
            std::nth_element(first, kth, last, [&](const T &a, const T &b) { return key(a) < key(b); });
            return;
        }
        // Median of the first, middle and last keys.
        float a = key(first[0]), b = key(first[(last - first) / 2]), c = key(last[-1]);
        if (b < a) std::swap(a, b);
        if (c < b) b = c < a ? a : c;
        const float pivot = b;
        T *lt = partition([pivot](float k) { return k < pivot; });  // [first, lt): below the pivot
        if (kth < lt) {
            last = lt;
            continue;
        }
        // kth >= lt: the part below stays before kth. Where it is not empty the range shrank
        // (the pivot's own element is in the back part), and the next round picks a new pivot
        // there; only a pivot that is the range's minimum needs the equal keys split off.
        if (lt > first) {
            first = lt;
            continue;
        }
        T *le = partition([pivot](float k) { return !(pivot < k); });  // [first, le): equal to it
        if (kth <= le) return;  // the equal keys reach kth: any of them may stand there
        first = le;
    }
}

} // namespace nori
