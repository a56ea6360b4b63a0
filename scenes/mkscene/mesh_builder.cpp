/// \file mesh_builder.cpp
/// \brief Vertex normals and OBJ output of nori-mkscene's meshes.
#include "mesh_builder.h"
#include <app/cli_app.h>
#include <nori/atomic_file.h>
#include <charconv>
#include <cstdio>

namespace mkscene {

std::vector<V3> MeshBuilder::vertexNormals() const {
    std::vector<V3> n(pos.size());
    for (const auto &f : tri) {
        // The cross product's length is twice the area: larger faces weigh more.
        V3 fn = cross(pos[f[1]] - pos[f[0]], pos[f[2]] - pos[f[0]]);
        for (uint32_t v : f) n[v] = n[v] + fn;
    }
    for (V3 &v : n) v = normalize(v);
    return n;
}

namespace {

/// Everything is formatted into one buffer and written with a single fwrite.
struct Writer {
    std::string buf;
    char tmp[64];
    void text(const char *s) { buf.append(s); }
    void real(double v) {
        // Shortest round-trip form of the float the renderer will read back.
        auto r = std::to_chars(tmp, tmp + sizeof(tmp), float(v));
        buf.push_back(' ');
        buf.append(tmp, r.ptr);
    }
    void vec(const char *tag, V3 v) {
        text(tag);
        real(v.x), real(v.y), real(v.z);
        text("\n");
    }
    void index(uint32_t i, bool withNormal) {
        auto r = std::to_chars(tmp, tmp + sizeof(tmp), i + 1);  // OBJ indices are 1-based
        buf.push_back(' ');
        buf.append(tmp, r.ptr);
        if (withNormal) {
            buf.append("//");
            buf.append(tmp, r.ptr);
        }
    }
};

} // namespace

bool MeshBuilder::writeObj(const std::string &path, const std::string &comment, bool withNormals) const {
    Writer w;
    w.buf.reserve(pos.size() * (withNormals ? 64 : 32) + tri.size() * 40 + 256);
    w.text("# nori-mkscene: ");
    w.text(comment.c_str());
    w.text("\n");
    for (const V3 &p : pos) w.vec("v", p);
    if (withNormals)
        for (const V3 &n : vertexNormals()) w.vec("vn", n);
    for (const auto &f : tri) {
        w.text("f");
        for (uint32_t v : f) w.index(v, withNormals);
        w.text("\n");
    }
    try {
        nori::AtomicFile::write(path, w.buf);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "nori-mkscene: %s\n", nori::oneLine(e.what()).c_str());
        return false;
    }
    std::printf("nori-mkscene: wrote %s (%zu vertices, %zu triangles)\n", path.c_str(), pos.size(), tri.size());
    return true;
}

} // namespace mkscene
