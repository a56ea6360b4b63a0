/// \file main.cpp
/// \brief nori-mkscene: writes the default scene's meshes (knot, pedestal, studio, lights) as OBJ.
//
//   nori-mkscene OUTDIR
//
// Deterministic for a given build. Each file is written atomically (nori::AtomicFile), so
// a failed run never leaves a truncated mesh behind for the renderer.

#include "knot.h"
#include "studio.h"
#include <app/cli_app.h>
#include <cstdio>

using namespace mkscene;

namespace {

// The set, in scene units (the knot's footprint is 1). The pedestal top is y = 0.
constexpr double kPedestalRadius = 0.62, kPedestalHeight = 0.07, kPedestalBevel = 0.012;
constexpr double kFloorY = -kPedestalHeight;
const V3 kLookAt{0.0, 0.2, 0.0};  // where the light panels point

struct Output {
    const char *file;
    const char *comment;
    bool normals;
    MeshBuilder mesh;
};

} // namespace

int main(int argc, char **argv) {
    nori::CliApp cli("nori-mkscene", "Writes the default scene's meshes (knot, pedestal, studio sweep, light panels) "
                                     "as OBJ files into a folder.");
    std::string dir;
    cli.app()
        .add_option("output", dir, "the folder to write them to")
        ->required()
        ->check(CLI::ExistingDirectory)
        ->option_text("OUTDIR");
    if (std::optional<int> status = cli.parse(argc, argv)) return *status;

    Output knot{"knot.obj", "trefoil knot tube with spiral ridges and beads", true, {}};
    // 1040 rings x 144 around gives roughly square quads along the ~16-unit-long,
    // 1.9-unit-round tube: 299,520 triangles. It hovers 0.012 above the pedestal.
    buildKnot(knot.mesh, 1040, 144, 0.0, 0.012);

    Output pedestal{"pedestal.obj", "round bevelled pedestal", true, {}};
    buildPedestal(pedestal.mesh, kPedestalRadius, kPedestalHeight, kPedestalBevel, 192);

    Output studio{"studio.obj", "photo-studio sweep: floor curving up into the back wall", true, {}};
    buildCyclorama(studio.mesh, kFloorY, 6.0, -2.2, 0.9, 4.0, 6.0, 24);

    // Softboxes: a large key light front-left and above, a smaller fill on the right, a
    // narrow rim strip behind the knot (seen from the default camera at about (1.0, 1.25, 1.76)).
    Output key{"light-key.obj", "key light panel", false, {}};
    buildPanel(key.mesh, {-1.4, 1.9, 1.0}, kLookAt, 1.4, 1.0);
    Output fill{"light-fill.obj", "fill light panel", false, {}};
    buildPanel(fill.mesh, {1.6, 0.8, -0.9}, kLookAt, 0.8, 0.8);
    Output rim{"light-rim.obj", "rim light strip", false, {}};
    buildPanel(rim.mesh, {-0.8, 1.3, -1.5}, kLookAt, 1.4, 0.3);

    for (Output *o : {&knot, &pedestal, &studio, &key, &fill, &rim})
        if (!o->mesh.writeObj(dir + "/" + o->file, o->comment, o->normals)) return 1;
    return 0;
}
