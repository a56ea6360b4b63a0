/// \file bbox.h
/// \brief Axis-aligned bounding box.
#pragma once

#include <nori/ray.h>
#include <algorithm>

namespace nori {

/// \brief Axis-aligned box [min, max]; an empty box has min > max.
struct BoundingBox3f {
    Point3f min = Point3f::Constant(Infinity);
    Point3f max = Point3f::Constant(-Infinity);

    BoundingBox3f() = default;
    BoundingBox3f(const Point3f &lo, const Point3f &hi) : min(lo), max(hi) {}

    bool isValid() const { return (max.array() >= min.array()).all(); }
    void expandBy(const Point3f &p) { min = min.cwiseMin(p); max = max.cwiseMax(p); }
    void expandBy(const BoundingBox3f &b) { min = min.cwiseMin(b.min); max = max.cwiseMax(b.max); }
    Point3f center() const { return 0.5f * (min + max); }
    Vector3f extents() const { return max - min; }
    int majorAxis() const {
        Vector3f e = extents();
        return e.x() >= e.y() && e.x() >= e.z() ? 0 : (e.y() >= e.z() ? 1 : 2);
    }
    bool contains(const Point3f &p) const {
        return (p.array() >= min.array()).all() && (p.array() <= max.array()).all();
    }
    bool overlaps(const BoundingBox3f &b) const {
        return (b.max.array() >= min.array()).all() && (b.min.array() <= max.array()).all();
    }

    /// \brief Slab test (Williams et al. 2005): the ray's parameter interval inside the box,
    /// clipped to [ray.mint, ray.maxt]. Returns false when it is empty.
    bool rayIntersect(const Ray3f &ray, float &nearT, float &farT) const {
        nearT = ray.mint;
        farT = ray.maxt;
        for (int i = 0; i < 3; ++i) {
            float t0 = (min[i] - ray.o[i]) * ray.dRcp[i];
            float t1 = (max[i] - ray.o[i]) * ray.dRcp[i];
            if (t0 > t1) std::swap(t0, t1);
            // NaN (0 * inf when the origin lies on a slab plane) must not shrink the interval.
            nearT = t0 > nearT ? t0 : nearT;
            farT = t1 < farT ? t1 : farT;
        }
        return nearT <= farT;
    }
};

} // namespace nori
