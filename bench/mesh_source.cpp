#include "mesh_source.h"
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <zlib.h>

#if __has_include(<nori/objloader.h>)
#include <nori/objloader.h>
#define NORI_BENCH_HAVE_OBJLOADER 1
#else
#define NORI_BENCH_HAVE_OBJLOADER 0
#endif

namespace nori::bench {

std::vector<const Mesh *> BenchInput::meshPointers() const {
    std::vector<const Mesh *> out;
    for (const auto &m : meshes) out.push_back(m.get());
    return out;
}

uint64_t BenchInput::triangleCount() const {
    uint64_t n = 0;
    for (const auto &m : meshes) n += m->triangleCount();
    return n;
}

namespace {

#if !NORI_BENCH_HAVE_OBJLOADER
/// Minimal OBJ reader used only until the project's loader is available: positions and
/// faces (fan-triangulated), 1-based or negative indices, gzip through zlib.
MeshData readObjFallback(const std::string &path) {
    gzFile file = gzopen(path.c_str(), "rb");
    if (!file) throw NoriException("{}: cannot open", path);
    gzbuffer(file, 1 << 20);
    MeshData data;
    std::vector<char> line(1 << 16);
    size_t lineNo = 0;
    auto resolve = [&](long idx) -> uint32_t {
        long n = long(data.positions.size());
        long r = idx > 0 ? idx - 1 : n + idx;
        if (idx == 0 || r < 0 || r >= n) {
            gzclose(file);
            throw NoriException("{}:{}: vertex index {} out of range", path, lineNo, idx);
        }
        return uint32_t(r);
    };
    while (gzgets(file, line.data(), int(line.size()))) {
        ++lineNo;
        const char *s = line.data();
        while (*s == ' ' || *s == '\t') ++s;
        if (s[0] == 'v' && (s[1] == ' ' || s[1] == '\t')) {
            char *end;
            float x = std::strtof(s + 2, &end);
            float y = std::strtof(end, &end);
            float z = std::strtof(end, &end);
            data.positions.emplace_back(x, y, z);
        } else if (s[0] == 'f' && (s[1] == ' ' || s[1] == '\t')) {
            std::vector<uint32_t> poly;
            const char *p = s + 2;
            while (true) {
                while (*p == ' ' || *p == '\t') ++p;
                if (*p == '\0' || *p == '\n' || *p == '\r') break;
                char *end;
                long idx = std::strtol(p, &end, 10);
                if (end == p) {
                    gzclose(file);
                    throw NoriException("{}:{}: bad face record", path, lineNo);
                }
                poly.push_back(resolve(idx));
                p = end;
                while (*p && *p != ' ' && *p != '\t' && *p != '\n' && *p != '\r') ++p;  // skip /vt/vn
            }
            for (size_t k = 2; k < poly.size(); ++k) data.faces.push_back({poly[0], poly[k - 1], poly[k]});
        }
    }
    gzclose(file);
    if (data.faces.empty()) throw NoriException("{}: no faces", path);
    return data;
}
#endif

std::string baseName(const std::string &path) {
    size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

} // namespace

BenchInput MeshSource::loadMesh(const std::string &path) {
    BenchInput input;
    input.name = path;
    auto start = std::chrono::steady_clock::now();
#if NORI_BENCH_HAVE_OBJLOADER
    MeshData data = loadObjFile(path);
#else
    MeshData data = readObjFallback(path);
#endif
    auto mesh = std::make_unique<Mesh>(std::move(data), baseName(path));
    input.loadMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (mesh->triangleCount() == 0) throw NoriException("{}: the mesh has no triangles", path);
    input.meshes.push_back(std::move(mesh));
    return input;
}

bool MeshSource::hasSceneParser() { return false; }

BenchInput MeshSource::loadScene(const std::string &path) {
    throw NoriException("--scene {}: this build has no scene parser yet (main has no loadScene); use --mesh", path);
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
    input.meshes.push_back(std::make_unique<Mesh>(std::move(data), "generated"));
    input.loadMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return input;
}

} // namespace nori::bench
