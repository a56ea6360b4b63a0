/// \file office.cpp
/// \brief "office": one storey of many small rooms behind thin walls with door openings,
/// along corridors, under one floor and one ceiling quad; camera at eye height in the middle
/// corridor, looking down it. Walls 12 cm thick stand 4-5 m apart across the whole floor:
/// pairs of close parallel faces everywhere, rays that start between them, and long views
/// down corridors past hundreds of walls.
#include "shape_generators.h"
#include "gen_random.h"
#include "mesh_builder.h"
#include <cmath>

namespace nori::gen {

namespace {
const float RoomW = 4.0f, RoomD = 5.0f, Corridor = 2.4f, Height = 3.0f, Wall = 0.12f;
const float DoorW = 0.9f, DoorH = 2.1f;
const uint64_t TrianglesPerRoom = 800;  // sets how many rooms a budget buys

/// A wall from \p a to \p b along x (\p alongX) or z, centred on the line, with a door
/// opening centred at \p door (distance from \p a; negative: no door).
void wall(MeshBuilder &b, bool alongX, float fixed, float a, float c, float door) {
    auto box = [&](float from, float to, float y0, float y1) {
        if (to - from <= 1e-3f) return;
        if (alongX)
            b.box(Point3f(from, y0, fixed - 0.5f * Wall), Point3f(to, y1, fixed + 0.5f * Wall), false);
        else
            b.box(Point3f(fixed - 0.5f * Wall, y0, from), Point3f(fixed + 0.5f * Wall, y1, to), false);
    };
    if (door < 0.0f) {
        box(a, c, 0.0f, Height);
        return;
    }
    float d0 = a + door - 0.5f * DoorW, d1 = a + door + 0.5f * DoorW;
    box(a, d0, 0.0f, Height);
    box(d1, c, 0.0f, Height);
    box(d0, d1, DoorH, Height);  // lintel
}

/// A round object to be added once the rest of the budget is known.
struct Ball {
    Point3f center;
    float radius;
};

/// Desk, chair, monitor and cabinet in the room whose corner is (x0, z0); the round things
/// on the desk (cups, a lamp shade, a plant) go to \p balls.
void furnish(MeshBuilder &b, GenRandom &rng, float x0, float z0, std::vector<Ball> &balls) {
    float dx = x0 + rng.range(0.6f, RoomW - 2.2f), dz = z0 + rng.range(0.6f, RoomD - 1.6f);
    const float top = 0.74f;
    b.box(Point3f(dx, top - 0.03f, dz), Point3f(dx + 1.6f, top, dz + 0.8f));
    for (float lx : {dx + 0.05f, dx + 1.51f})
        for (float lz : {dz + 0.05f, dz + 0.71f}) b.box(Point3f(lx, 0, lz), Point3f(lx + 0.04f, top - 0.03f, lz + 0.04f));
    float mx = dx + rng.range(0.3f, 0.9f);
    b.box(Point3f(mx, top, dz + 0.2f), Point3f(mx + 0.5f, top + 0.35f, dz + 0.23f));
    float cx = dx + rng.range(0.4f, 1.2f), cz = dz + 1.1f;
    b.cylinder(Point3f(cx, 0, cz), 0.03f, 0.45f, 8);
    b.box(Point3f(cx - 0.22f, 0.45f, cz - 0.22f), Point3f(cx + 0.22f, 0.5f, cz + 0.22f));
    b.box(Point3f(x0 + 0.2f, 0, z0 + RoomD - 0.7f), Point3f(x0 + 1.0f, 1.1f, z0 + RoomD - 0.2f));
    for (int k = 0; k < 4; ++k) {
        float r = rng.range(0.03f, 0.12f);
        balls.push_back({Point3f(dx + rng.range(0.15f, 1.45f), top + r, dz + rng.range(0.15f, 0.65f)), r});
    }
}
} // namespace

GeneratedScene generateOffice(const GenParams &params) {
    // Rooms in pairs of rows (back to back) between corridors along x: rows of `cols` rooms.
    uint64_t rooms = std::max<uint64_t>(4, params.triangles / TrianglesPerRoom);
    int pairs = std::max(1, int(std::lround(std::sqrt(double(rooms) / 8.0))));
    int cols = std::max(2, int(rooms / uint64_t(2 * pairs)));
    float width = float(cols) * RoomW, band = Corridor + 2.0f * RoomD;
    float depth = float(pairs) * band + Corridor;
    GenRandom rng(params.seed, 13);
    MeshBuilder b;
    // Floor and ceiling: one quad each over the whole storey, facing inwards.
    b.quad(Point3f(0, 0, 0), Point3f(0, 0, depth), Point3f(width, 0, depth), Point3f(width, 0, 0));
    b.quad(Point3f(0, Height, 0), Point3f(width, Height, 0), Point3f(width, Height, depth), Point3f(0, Height, depth));
    // Outer walls.
    wall(b, true, 0.0f, 0.0f, width, -1.0f);
    wall(b, true, depth, 0.0f, width, -1.0f);
    wall(b, false, 0.0f, 0.0f, depth, -1.0f);
    wall(b, false, width, 0.0f, depth, -1.0f);
    std::vector<Ball> balls;
    for (int p = 0; p < pairs; ++p) {
        float z0 = Corridor + float(p) * band;  // the corridor before this pair is [z0 - Corridor, z0]
        // The long walls: corridor side of each row (a door into every room) and the back wall.
        for (int row = 0; row < 2; ++row) {
            float zWall = row == 0 ? z0 : z0 + 2.0f * RoomD;
            for (int c = 0; c < cols; ++c)
                wall(b, true, zWall, float(c) * RoomW, float(c + 1) * RoomW, rng.range(0.7f, RoomW - 0.7f));
        }
        wall(b, true, z0 + RoomD, 0.0f, width, -1.0f);
        // Partitions between neighbouring rooms; every third one has a connecting door.
        for (int row = 0; row < 2; ++row)
            for (int c = 1; c < cols; ++c) {
                float door = rng.below(3) == 0 ? rng.range(0.8f, RoomD - 0.8f) : -1.0f;
                wall(b, false, float(c) * RoomW, z0 + float(row) * RoomD, z0 + float(row + 1) * RoomD, door);
            }
        for (int row = 0; row < 2; ++row)
            for (int c = 0; c < cols; ++c) furnish(b, rng, float(c) * RoomW, z0 + float(row) * RoomD, balls);
    }
    // The round objects share what is left of the budget; each takes its share of what
    // remains, so the rounding of one is made up by the next.
    for (size_t k = 0; k < balls.size(); ++k) {
        uint64_t left = params.triangles > b.triangleCount() ? params.triangles - b.triangleCount() : 0;
        double share = double(left) / double(balls.size() - k);
        b.sphere(balls[k].center, balls[k].radius, std::max(1, int(std::lround(std::sqrt(share / 12.0)))));
    }
    // The camera stands at one end of a middle corridor and looks down it.
    float corridorZ = Corridor + float(pairs / 2) * band - 0.5f * Corridor;
    GeneratedScene s;
    s.shape = "office";
    s.description = "storey of small rooms behind thin walls with doors, camera down a corridor";
    s.mesh = b.take();
    s.camera.origin = Point3f(0.8f, 1.6f, corridorZ + 0.3f);
    s.camera.target = Point3f(width, 1.3f, corridorZ - 0.2f);
    s.camera.fov = 70.0f;
    s.camera.nearClip = 1e-3f;
    s.aoLength = 0.8f;
    return s;
}

} // namespace nori::gen
