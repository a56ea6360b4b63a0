/// \file room.cpp
/// \brief "room": a 10 x 3 x 8 room of twelve huge wall triangles around tables, chairs, a
/// bookshelf and small, finely tessellated objects on the tables, with the camera inside:
/// large and tiny triangles in one scene, and every ray starts within the bounds.
#include "shape_generators.h"
#include "gen_random.h"
#include "mesh_builder.h"
#include <cmath>

namespace nori::gen {

namespace {
const float RoomX = 5.0f, RoomY = 3.0f, RoomZ = 4.0f;
const int TableCols = 3, TableRows = 2, ObjectsPerTable = 12;
const float TableHeight = 0.75f, TopThickness = 0.05f, HalfTableX = 0.8f, HalfTableZ = 0.45f;

/// Table top and four legs around (cx, cz).
void table(MeshBuilder &b, float cx, float cz) {
    float top = TableHeight;
    b.box(Point3f(cx - HalfTableX, top - TopThickness, cz - HalfTableZ), Point3f(cx + HalfTableX, top, cz + HalfTableZ));
    for (int sx : {-1, 1})
        for (int sz : {-1, 1}) {
            float lx = cx + float(sx) * (HalfTableX - 0.08f), lz = cz + float(sz) * (HalfTableZ - 0.08f);
            b.box(Point3f(lx - 0.03f, 0, lz - 0.03f), Point3f(lx + 0.03f, top - TopThickness, lz + 0.03f));
        }
}

/// Seat, four legs and a back rest; \p facing is +1 or -1 along z.
void chair(MeshBuilder &b, float cx, float cz, float facing) {
    const float seat = 0.45f, h = 0.22f;
    b.box(Point3f(cx - h, seat - 0.04f, cz - h), Point3f(cx + h, seat, cz + h));
    for (int sx : {-1, 1})
        for (int sz : {-1, 1}) {
            float lx = cx + float(sx) * (h - 0.03f), lz = cz + float(sz) * (h - 0.03f);
            b.box(Point3f(lx - 0.02f, 0, lz - 0.02f), Point3f(lx + 0.02f, seat - 0.04f, lz + 0.02f));
        }
    float backZ = cz - facing * (h - 0.02f);
    b.box(Point3f(cx - h, seat, backZ - 0.02f), Point3f(cx + h, seat + 0.5f, backZ + 0.02f));
}
} // namespace

GeneratedScene generateRoom(const GenParams &params) {
    GenRandom rng(params.seed, 5);
    MeshBuilder b;
    // Floor, ceiling and four walls: two triangles each, facing inwards.
    auto p = [](int x, int y, int z) {
        return Point3f(x ? RoomX : -RoomX, y ? RoomY : 0.0f, z ? RoomZ : -RoomZ);
    };
    b.quad(p(0, 0, 0), p(0, 0, 1), p(1, 0, 1), p(1, 0, 0));
    b.quad(p(0, 1, 0), p(1, 1, 0), p(1, 1, 1), p(0, 1, 1));
    b.quad(p(0, 0, 0), p(1, 0, 0), p(1, 1, 0), p(0, 1, 0));
    b.quad(p(0, 0, 1), p(0, 1, 1), p(1, 1, 1), p(1, 0, 1));
    b.quad(p(0, 0, 0), p(0, 1, 0), p(0, 1, 1), p(0, 0, 1));
    b.quad(p(1, 0, 0), p(1, 0, 1), p(1, 1, 1), p(1, 1, 0));

    std::vector<Point3f> tableCenters;
    for (int r = 0; r < TableRows; ++r)
        for (int c = 0; c < TableCols; ++c) {
            float cx = -2.8f + 2.8f * float(c), cz = -1.6f + 3.0f * float(r);
            table(b, cx, cz);
            chair(b, cx - 0.4f, cz + 0.8f, 1.0f);
            chair(b, cx + 0.4f, cz - 0.8f, -1.0f);
            tableCenters.emplace_back(cx, TableHeight, cz);
        }
    // A bookshelf against the back wall: four boards with thin books standing on them.
    for (int shelf = 0; shelf < 4; ++shelf) {
        float y = 0.3f + 0.6f * float(shelf);
        b.box(Point3f(-2.0f, y - 0.03f, -RoomZ + 0.02f), Point3f(2.0f, y, -RoomZ + 0.35f));
        for (float x = -1.95f; x < 1.9f;) {
            float w = rng.range(0.02f, 0.06f), h = rng.range(0.18f, 0.5f);
            b.box(Point3f(x, y, -RoomZ + 0.05f), Point3f(x + w, y + h, -RoomZ + rng.range(0.2f, 0.32f)));
            x += w + rng.range(0.0f, 0.02f);
        }
    }
    // Small objects on the tables share what is left of the budget.
    uint64_t objects = uint64_t(TableRows * TableCols * ObjectsPerTable);
    uint64_t left = params.triangles > b.triangleCount() ? params.triangles - b.triangleCount() : 0;
    int n = std::max(1, int(std::lround(std::sqrt(double(left / objects) / 12.0))));
    for (const Point3f &c : tableCenters)
        for (int k = 0; k < ObjectsPerTable; ++k) {
            float rx = rng.range(0.025f, 0.08f), ry = rx * rng.range(0.5f, 1.8f), rz = rx * rng.range(0.7f, 1.3f);
            Point3f center(c.x() + rng.range(-HalfTableX + 0.1f, HalfTableX - 0.1f), c.y() + ry,
                           c.z() + rng.range(-HalfTableZ + 0.1f, HalfTableZ - 0.1f));
            b.cubeSphere(n, [&](const Vector3f &d) {
                return Point3f(center + Vector3f(rx * d.x(), ry * d.y(), rz * d.z()));
            });
        }
    GeneratedScene s;
    s.shape = "room";
    s.description = "room with large walls, tables, chairs, a bookshelf and small objects; camera inside";
    s.mesh = b.take();
    s.camera.origin = Point3f(-4.4f, 1.75f, 3.5f);
    s.camera.target = Point3f(1.0f, 0.6f, -1.2f);
    s.camera.fov = 75.0f;
    s.camera.nearClip = 1e-3f;
    s.aoLength = 0.6f;
    return s;
}

} // namespace nori::gen
