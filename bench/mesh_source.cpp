/// \file mesh_source.cpp
/// \brief Where nori-bench gets its geometry: OBJ files, a Nori scene, or a generated mesh (implementation).
#include "mesh_source.h"
#include <nori/objloader.h>
#include <nori/parser.h>
#include <scene_geometry.h>
#include <chrono>
#include <cmath>

namespace nori::bench {

std::vector<const Mesh *> BenchInput::meshPointers() const {
    std::vector<const Mesh *> out;
    for (const auto &m : ownedMeshes) out.push_back(m.get());
    if (scene)
        for (const auto &m : scene->meshes()) out.push_back(m.get());
    return out;
}

uint64_t BenchInput::triangleCount() const {
    uint64_t n = 0;
    for (const Mesh *m : meshPointers()) n += m->triangleCount();
    return n;
}

namespace {

std::string baseName(const std::string &path) {
    size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

} // namespace

BenchInput MeshSource::loadMesh(const std::string &path) {
    BenchInput input;
    input.name = path;
    auto start = std::chrono::steady_clock::now();
    MeshData data = loadObjFile(path);
    auto mesh = std::make_unique<Mesh>(std::move(data), baseName(path));
    input.loadMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (mesh->triangleCount() == 0) throw NoriException("{}: the mesh has no triangles", path);
    input.ownedMeshes.push_back(std::move(mesh));
    return input;
}

BenchInput MeshSource::loadScene(const std::string &path) {
    BenchInput input;
    input.name = path;
    auto start = std::chrono::steady_clock::now();
    input.scene = loadSceneGeometry(path);
    input.loadMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (input.triangleCount() == 0) throw NoriException("{}: the scene has no triangles", path);
    return input;
}

BenchInput MeshSource::generatedShape(const std::string &shape, const gen::GenParams &params) {
    BenchInput input;
    input.name = params.triangles ? fmt::format("shape:{}:{}", shape, params.triangles) : "shape:" + shape;
    if (params.seed != 1) input.name += fmt::format(" (seed {})", params.seed);
    auto start = std::chrono::steady_clock::now();
    gen::GeneratedScene scene = gen::generateScene(shape, params);
    input.ownedCamera = gen::makeCamera(scene.camera);
    input.ownedMeshes.push_back(std::make_unique<Mesh>(std::move(scene.mesh), shape));
    input.loadMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return input;
}

BenchInput MeshSource::generated() {
    BenchInput input;
    input.name = "generated";
    auto start = std::chrono::steady_clock::now();
    MeshData data;
    // A sphere with a bumpy radius (longitude x latitude grid) ...
    const int nu = 96, nv = 48;
    for (int j = 0; j <= nv; ++j) {
        float theta = Pi * float(j) / nv;
        for (int i = 0; i < nu; ++i) {
            float phi = 2.0f * Pi * float(i) / nu;
            float r = 1.0f + 0.12f * std::sin(5.0f * phi) * std::sin(4.0f * theta);
            data.positions.emplace_back(r * std::sin(theta) * std::cos(phi), r * std::cos(theta),
                                        r * std::sin(theta) * std::sin(phi));
        }
    }
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            uint32_t a = uint32_t(j * nu + i), b = uint32_t(j * nu + (i + 1) % nu);
            uint32_t c = a + nu, d = b + nu;
            data.faces.push_back({a, c, b});
            data.faces.push_back({b, c, d});
        }
    // ... standing on a finely tessellated ground plane, so shadow rays have something to do.
    const int g = 24;
    uint32_t base = uint32_t(data.positions.size());
    for (int j = 0; j <= g; ++j)
        for (int i = 0; i <= g; ++i)
            data.positions.emplace_back(-3.0f + 6.0f * i / g, -1.2f, -3.0f + 6.0f * j / g);
    for (int j = 0; j < g; ++j)
        for (int i = 0; i < g; ++i) {
            uint32_t a = base + uint32_t(j * (g + 1) + i), b = a + 1, c = a + (g + 1), d = c + 1;
            data.faces.push_back({a, c, b});
            data.faces.push_back({b, c, d});
        }
    input.ownedMeshes.push_back(std::make_unique<Mesh>(std::move(data), "generated"));
    input.loadMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return input;
}

} // namespace nori::bench
