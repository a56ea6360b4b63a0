/// \file embree_oracle.cpp
/// \brief Embree 3 as the reference intersector (tests and benchmark only; the renderer never links it) (implementation).
#include "embree_oracle.h"
#include <embree3/rtcore.h>
#include <chrono>
#include <cstring>
#include <nori/cpu_clock.h>

namespace nori {

bool EmbreeOracle::memoryMonitor(void *self, ssize_t bytes, bool) {
    static_cast<EmbreeOracle *>(self)->m_bytes += bytes;
    return true;
}

EmbreeOracle::EmbreeOracle(const std::vector<const Mesh *> &meshes, const Options &options) {
    std::string config = options.threads > 0 ? fmt::format("threads={}", options.threads) : std::string();
    m_device = rtcNewDevice(config.c_str());
    if (!m_device) throw NoriException("cannot create an Embree device ({})", int(rtcGetDeviceError(nullptr)));
    rtcSetDeviceMemoryMonitorFunction(m_device, &EmbreeOracle::memoryMonitor, this);

    const double cpuStart = threadCpuMilliseconds();
    auto start = std::chrono::steady_clock::now();
    m_scene = rtcNewScene(m_device);
    if (options.robust) rtcSetSceneFlags(m_scene, RTC_SCENE_FLAG_ROBUST);
    uint32_t offset = 0;
    for (const Mesh *mesh : meshes) {
        RTCGeometry geom = rtcNewGeometry(m_device, RTC_GEOMETRY_TYPE_TRIANGLE);
        // Embree reads vertices with 16-byte loads: its buffers are padded, so copy into them.
        auto *v = static_cast<float *>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), mesh->vertexCount()));
        std::memcpy(v, mesh->positions().data(), sizeof(float) * 3 * mesh->vertexCount());
        auto *f = static_cast<uint32_t *>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                  3 * sizeof(uint32_t), mesh->triangleCount()));
        std::memcpy(f, mesh->faces().data(), sizeof(uint32_t) * 3 * mesh->triangleCount());
        rtcCommitGeometry(geom);
        rtcAttachGeometry(m_scene, geom);
        rtcReleaseGeometry(geom);
        m_offsets.push_back(offset);
        offset += mesh->triangleCount();
    }
    rtcCommitScene(m_scene);
    m_buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    m_buildCpuMs = threadCpuMilliseconds() - cpuStart;
    m_bytesAfterBuild = m_bytes;
}

EmbreeOracle::~EmbreeOracle() {
    if (m_scene) rtcReleaseScene(m_scene);
    if (m_device) rtcReleaseDevice(m_device);
}

namespace {
void toEmbreeRay(const Ray3f &ray, RTCRay &r) {
    r.org_x = ray.o.x(); r.org_y = ray.o.y(); r.org_z = ray.o.z();
    r.dir_x = ray.d.x(); r.dir_y = ray.d.y(); r.dir_z = ray.d.z();
    r.tnear = ray.mint;
    r.tfar = ray.maxt;
    r.time = 0.0f;
    r.mask = ~0u;
    r.id = 0;
    r.flags = 0;
}
} // namespace

bool EmbreeOracle::intersect(const Ray3f &ray, Hit &hit) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    toEmbreeRay(ray, rh.ray);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(m_scene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    hit.t = rh.ray.tfar;
    hit.u = rh.hit.u;
    hit.v = rh.hit.v;
    hit.prim = m_offsets[rh.hit.geomID] + rh.hit.primID;
    return true;
}

bool EmbreeOracle::occluded(const Ray3f &ray) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay r;
    toEmbreeRay(ray, r);
    rtcOccluded1(m_scene, &context, &r);
    return r.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

} // namespace nori
