/// \file embree_oracle.h
/// \brief Embree 3 as the reference intersector (tests and benchmark only; the renderer never links it).
#pragma once

#include <nori/accel.h>
#include <sys/types.h>

struct RTCDeviceTy;
struct RTCSceneTy;

namespace nori {

/// \brief An Embree scene over the same meshes, numbering triangles like nori::Accel
/// (meshes in order, triangles in order within a mesh).
class EmbreeOracle {
public:
    struct Options {
        bool robust = true;  ///< RTC_SCENE_FLAG_ROBUST (the oracle); false for raw speed
        int threads = 0;     ///< 0: Embree's default; 1: single-threaded build and queries
    };

    EmbreeOracle(const std::vector<const Mesh *> &meshes, const Options &options);
    explicit EmbreeOracle(const std::vector<const Mesh *> &meshes) : EmbreeOracle(meshes, Options()) {}
    ~EmbreeOracle();
    EmbreeOracle(const EmbreeOracle &) = delete;
    EmbreeOracle &operator=(const EmbreeOracle &) = delete;

    /// \brief Closest hit in [ray.mint, ray.maxt] (rtcIntersect1).
    bool intersect(const Ray3f &ray, Hit &hit) const;
    /// \brief Any hit in [ray.mint, ray.maxt] (rtcOccluded1).
    bool occluded(const Ray3f &ray) const;

    double buildMilliseconds() const { return m_buildMs; }
    /// \brief The calling thread's CPU time during the build (with threads=1 Embree builds on it).
    double buildCpuMilliseconds() const { return m_buildCpuMs; }
    /// \brief Bytes Embree holds after the build, from its device memory monitor.
    long long bytes() const { return m_bytesAfterBuild; }

private:
    RTCDeviceTy *m_device = nullptr;
    RTCSceneTy *m_scene = nullptr;
    std::vector<uint32_t> m_offsets;  ///< first global triangle id of each geometry
    double m_buildMs = 0.0;
    double m_buildCpuMs = 0.0;
    long long m_bytesAfterBuild = 0;
    long long m_bytes = 0;  ///< running total kept by the memory monitor callback
    static bool memoryMonitor(void *self, ssize_t bytes, bool post);
};

} // namespace nori
