/// \file towers.cpp
/// \brief "towers": a cluster of skyscrapers, the tallest 900 high on a plaza 120 across,
/// seen whole in a portrait frame: the wide shape turned on end (bounds about 7x taller than
/// wide), every tower a stack of thin floor slabs, inset glass and window fins, so most
/// triangles are long, thin and axis-aligned, stacked in parallel planes a few metres apart.
#include "shape_generators.h"
#include "gen_random.h"
#include "mesh_builder.h"
#include <algorithm>
#include <cmath>

namespace nori::gen {

namespace {
const float Plaza = 60.0f, Storey = 4.0f, Slab = 0.4f, Inset = 0.6f;

struct Tower {
    float x, z, halfX, halfZ, height;
};
} // namespace

GeneratedScene generateTowers(const GenParams &params) {
    GenRandom rng(params.seed, 14);
    // Seven towers on a 3 x 3 grid of lots (two lots stay empty), the first one the tallest.
    std::vector<Tower> towers;
    std::vector<int> lots = {4, 0, 1, 2, 3, 5, 6, 7, 8};
    for (int k = 0; k < 7; ++k) {
        int lot = lots[size_t(k == 0 ? 0 : 1 + rng.below(uint32_t(lots.size() - 1)))];
        lots.erase(std::find(lots.begin(), lots.end(), lot));
        float cx = -40.0f + 40.0f * float(lot % 3), cz = -40.0f + 40.0f * float(lot / 3);
        float height = k == 0 ? 900.0f : rng.range(120.0f, 520.0f);
        towers.push_back({cx + rng.range(-4.0f, 4.0f), cz + rng.range(-4.0f, 4.0f), rng.range(10.0f, 17.0f),
                          rng.range(10.0f, 17.0f), height});
    }
    // Storeys 4 high; a small budget groups several storeys under one slab, a large one
    // spends the rest on vertical window fins (12 triangles each) spread over every facade.
    double storeys = 0.0;
    for (const Tower &t : towers) storeys += std::floor(t.height / Storey);
    const double perStorey = 12 + 8;  // slab and the four glass quads of one storey
    int group = std::max(1, int(std::ceil(perStorey * storeys / double(params.triangles))));
    double fins = std::max(0.0, (double(params.triangles) - perStorey * storeys / double(group) - 2.0) / 12.0);
    double finsPerSide = fins / (4.0 * storeys / double(group));
    MeshBuilder b;
    b.quad(Point3f(-Plaza, 0, -Plaza), Point3f(-Plaza, 0, Plaza), Point3f(Plaza, 0, Plaza), Point3f(Plaza, 0, -Plaza));
    double finDebt = 0.0;  // fractional fins carried from facade to facade
    for (const Tower &t : towers) {
        int levels = int(std::floor(t.height / Storey)) / group;
        float h = Storey * float(group);
        for (int level = 0; level < levels; ++level) {
            float y0 = h * float(level), y1 = y0 + h;
            // The slab sticks out past the facade; the glass is set back behind it.
            b.box(Point3f(t.x - t.halfX, y1 - Slab, t.z - t.halfZ), Point3f(t.x + t.halfX, y1, t.z + t.halfZ));
            float gx = t.halfX - Inset, gz = t.halfZ - Inset, g0 = y0, g1 = y1 - Slab;
            b.quad(Point3f(t.x - gx, g0, t.z + gz), Point3f(t.x + gx, g0, t.z + gz), Point3f(t.x + gx, g1, t.z + gz),
                   Point3f(t.x - gx, g1, t.z + gz));
            b.quad(Point3f(t.x + gx, g0, t.z - gz), Point3f(t.x - gx, g0, t.z - gz), Point3f(t.x - gx, g1, t.z - gz),
                   Point3f(t.x + gx, g1, t.z - gz));
            b.quad(Point3f(t.x + gx, g0, t.z + gz), Point3f(t.x + gx, g0, t.z - gz), Point3f(t.x + gx, g1, t.z - gz),
                   Point3f(t.x + gx, g1, t.z + gz));
            b.quad(Point3f(t.x - gx, g0, t.z - gz), Point3f(t.x - gx, g0, t.z + gz), Point3f(t.x - gx, g1, t.z + gz),
                   Point3f(t.x - gx, g1, t.z - gz));
            // Fins: thin vertical boxes standing out of the glass, evenly spaced on each side.
            for (int side = 0; side < 4; ++side) {
                finDebt += finsPerSide;
                int n = int(finDebt);
                finDebt -= double(n);
                bool alongX = side < 2;
                float half = alongX ? gx : gz, sign = side % 2 == 0 ? 1.0f : -1.0f;
                for (int f = 0; f < n; ++f) {
                    float u = -half + 2.0f * half * (float(f) + 0.5f) / float(n);
                    float face = sign * (alongX ? gz : gx);
                    Point3f lo = alongX ? Point3f(t.x + u - 0.05f, g0, t.z + face - 0.25f)
                                        : Point3f(t.x + face - 0.25f, g0, t.z + u - 0.05f);
                    Point3f hi = alongX ? Point3f(t.x + u + 0.05f, g1, t.z + face + 0.25f)
                                        : Point3f(t.x + face + 0.25f, g1, t.z + u + 0.05f);
                    b.box(lo, hi);
                }
            }
        }
    }
    GeneratedScene s;
    s.shape = "towers";
    s.description = "seven skyscrapers up to 900 high on a plaza 120 across (slabs, glass, fins)";
    s.mesh = b.take();
    // A portrait frame from the street, looking up at the whole cluster.
    s.camera.origin = Point3f(120.0f, 2.0f, 170.0f);
    s.camera.target = Point3f(0.0f, 300.0f, 0.0f);
    s.camera.fov = 45.0f;
    s.camera.width = 360;
    s.camera.height = 640;
    s.camera.nearClip = 0.1f;
    s.aoLength = 6.0f;
    return s;
}

} // namespace nori::gen
