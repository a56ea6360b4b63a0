/// \file test_triangle_widths.cpp
/// \brief The leaf kernels at every lane width compiled into this build (16 with AVX-512, 8
/// with AVX2, always 1) give bit-identical answers: per triangle, per chunk box, per leaf.
/// (The other builds of CI run the same test with their own widths; together they cover the
/// claim that an AVX-512, an AVX2 and a scalar machine render the same image.)
#include "triangle_cases.h"

#include <accel/triangle.h>

#include <cstring>

using namespace nori;
using namespace nori::decisions;

namespace {

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; }

TEST(TriangleWidths, TheBuildHasTheWidthsItsTargetAllows) {
    const std::vector<int> widths = TriangleStore::laneWidths();
    ASSERT_FALSE(widths.empty());
    EXPECT_EQ(widths.back(), 1);
#if defined(__AVX512F__) && defined(__AVX512VL__) && defined(__AVX512DQ__)
    EXPECT_EQ(widths, (std::vector<int>{16, 8, 1}));
#elif defined(__AVX2__)
    EXPECT_EQ(widths, (std::vector<int>{8, 1}));
#else
    EXPECT_EQ(widths, (std::vector<int>{1}));
#endif
    TriangleStore store;
    Hit hit;
    EXPECT_THROW(store.intersectLanes(4, TriangleRay(Ray3f(Point3f(0, 0, 0), Vector3f(0, 0, 1))), 0, 0, hit),
                 std::invalid_argument);
}

TEST(TriangleWidths, EveryTriangleGetsTheSameAnswerAtEveryWidth) {
    for (const CaseSet &set : allCaseSets())
        for (Intersector kind : {Intersector::Watertight, Intersector::MT}) {
            TriangleStore store = set.store(kind);
            size_t bad = 0, hits = 0;
            for (const Case &c : set.cases) {
                TriangleRay ray(c.ray);
                TriangleStore::ChunkAnswers ref;
                store.chunkAnswers(1, ray, CaseSet::offset(c.leaf), 16, 0, c.ray.maxt, ref);
                hits += unsigned(__builtin_popcount(ref.hits));
                for (int width : TriangleStore::laneWidths()) {
                    TriangleStore::ChunkAnswers ans;
                    store.chunkAnswers(width, ray, CaseSet::offset(c.leaf), 16, 0, c.ray.maxt, ans);
                    bool same = ans.hits == ref.hits;
                    for (int s = 0; s < 16; ++s)
                        if ((ref.hits >> s) & 1u)
                            same = same && sameBits(ans.t[s], ref.t[s]) && sameBits(ans.u[s], ref.u[s]) && sameBits(ans.v[s], ref.v[s]);
                    if (!same && ++bad <= 3)
                        ADD_FAILURE() << set.name << " " << intersectorName(kind) << " " << c.kind << ": " << width
                                      << " lanes differ from 1 lane";
                }
            }
            EXPECT_EQ(bad, 0u);
            EXPECT_GT(hits, 100u) << set.name;
        }
}

// Leaves of every length 1..40 (full and partial 8- and 16-lane steps, one and several chunks
// with their boxes) and one of all the rest: closest hit (t, u, v, triangle id) and any-hit.
TEST(TriangleWidths, LeavesGiveTheSameClosestAndAnyHitAtEveryWidth) {
    for (const CaseSet &set : allCaseSets()) {
        std::vector<uint32_t> prims(set.triangles.size());
        for (uint32_t i = 0; i < prims.size(); ++i) prims[i] = i;
        std::vector<std::pair<uint32_t, uint32_t>> ranges;  // (first, length)
        uint32_t begin = 0;
        for (uint32_t len = 1; begin + len <= prims.size() && len <= 40; begin += len, ++len) ranges.push_back({begin, len});
        if (begin < prims.size()) ranges.push_back({begin, uint32_t(prims.size()) - begin});
        std::vector<size_t> offsets;
        size_t words = 0;
        for (auto [first, len] : ranges) {
            offsets.push_back(words);
            words += TriangleStore::leafWords(len);
        }
        for (Intersector kind : {Intersector::Watertight, Intersector::MT}) {
            TriangleStore store;
            store.reset(kind, words);
            for (size_t l = 0; l < ranges.size(); ++l) store.setLeaf(offsets[l], prims.data() + ranges[l].first, ranges[l].second, set.triangles);
            size_t bad = 0, hits = 0;
            for (size_t c = 0; c < set.cases.size(); c += 3) {
                const Ray3f &ray = set.cases[c].ray;
                TriangleRay tr(ray);
                for (size_t l = 0; l < ranges.size(); ++l) {
                    Hit ref;
                    ref.t = ray.maxt;
                    const bool refFound = store.intersectLanes(1, tr, offsets[l], ranges[l].second, ref);
                    hits += refFound;
                    for (int width : TriangleStore::laneWidths()) {
                        Hit h;
                        h.t = ray.maxt;
                        const bool found = store.intersectLanes(width, tr, offsets[l], ranges[l].second, h);
                        const bool any = store.occludedLanes(width, tr, offsets[l], ranges[l].second, ray.maxt);
                        const bool same = found == refFound && any == refFound && sameBits(h.t, ref.t) && sameBits(h.u, ref.u) &&
                                          sameBits(h.v, ref.v) && h.prim == ref.prim;
                        if (!same && ++bad <= 3)
                            ADD_FAILURE() << set.name << " " << intersectorName(kind) << ", leaf of " << ranges[l].second
                                          << ": " << width << " lanes differ from 1 lane";
                    }
                }
            }
            EXPECT_EQ(bad, 0u) << set.name << " " << intersectorName(kind);
            EXPECT_GT(hits, 100u) << set.name;
        }
    }
}

} // namespace
