/// \file genscene.cpp
/// \brief nori-genscene: writes a generated scene (OBJ + Nori XML) that `nori` renders as is.
#include "scene_generator.h"
#include "scene_writer.h"
#include <CLI/CLI.hpp>
#include <cstdio>

using namespace nori;

int main(int argc, char **argv) {
    CLI::App app{"nori-genscene: deterministic generated scenes (OBJ + Nori XML) for the renderer, "
                 "nori-bench and the tests"};
    std::string shape, outDir, integrator;
    uint64_t triangles = 0, seed = 1;
    int spp = 16;
    bool list = false;
    std::vector<float> rotate, offset;
    app.add_option("shape", shape, "shape to generate, or 'all' (see --list)");
    app.add_option("out_dir", outDir, "folder for SHAPE.obj and SHAPE.xml (created if missing)");
    // (Checked as text: CLI11 reads "-5" into an unsigned as 2^64 - 5.)
    app.add_option("--triangles", triangles, "approximate triangle count (default: the shape's own)")
        ->check(CLI::Validator(
            [](const std::string &text) {
                const bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
                return digits && text.find_first_not_of('0') != std::string::npos
                           ? std::string()
                           : "expected a positive integer, got '" + text + "'";
            },
            ""));
    app.add_option("--seed", seed, "random seed (default 1)");
    app.add_option("--integrator", integrator, "integrator of the written scene (default: the shape's own)")
        ->check(CLI::IsMember({"ao", "normals"}));
    app.add_option("--spp", spp, "samples per pixel of the written scene")->check(CLI::Range(1, 1 << 16));
    app.add_option("--rotate", rotate,
                   "AX,AY,AZ,DEGREES: turn the whole scene (mesh and camera) about that axis, e.g. 1,2,0.5,33 "
                   "(walls and floors at an angle)")
        ->delimiter(',')
        ->expected(4);
    app.add_option("--offset", offset,
                   "X,Y,Z: then move it by that much, e.g. 100000,0,-200000 (a scene far from the origin)")
        ->delimiter(',')
        ->expected(3);
    app.add_flag("--list", list, "list the shapes and exit");
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp &e) {
        return app.exit(e);
    } catch (const CLI::ParseError &e) {
        std::fprintf(stderr, "nori-genscene: %s\n", e.what());
        return 2;
    }
    if (list) {
        for (const gen::ShapeInfo &s : gen::shapes())
            std::printf("%-12s %9llu  %s\n", s.name, (unsigned long long)s.defaultTriangles, s.summary);
        return 0;
    }
    if (shape.empty() || outDir.empty()) {
        std::fprintf(stderr, "nori-genscene: give SHAPE and OUT_DIR (see --help; --list for the shapes)\n");
        return 2;
    }
    if (shape != "all" && !gen::findShape(shape)) {
        std::fprintf(stderr, "nori-genscene: unknown shape '%s' (expected all or one of: %s)\n", shape.c_str(),
                     gen::shapeList().c_str());
        return 2;
    }
    try {
        for (const gen::ShapeInfo &info : gen::shapes()) {
            if (shape != "all" && shape != info.name) continue;
            gen::GenParams params;
            params.triangles = triangles;
            params.seed = seed;
            std::string placed;
            if (!rotate.empty()) {
                params.placement.axis = Vector3f(rotate[0], rotate[1], rotate[2]);
                params.placement.degrees = rotate[3];
                placed += fmt::format(" --rotate {},{},{},{}", rotate[0], rotate[1], rotate[2], rotate[3]);
            }
            if (!offset.empty()) {
                params.placement.offset = Vector3f(offset[0], offset[1], offset[2]);
                placed += fmt::format(" --offset {},{},{}", offset[0], offset[1], offset[2]);
            }
            gen::GeneratedScene scene = gen::generateScene(info.name, params);
            std::string comment = fmt::format("nori-genscene {} --triangles {} --seed {}{}", info.name,
                                              triangles ? triangles : info.defaultTriangles, seed, placed);
            gen::SceneWriter::write(scene, outDir, info.name, integrator.empty() ? scene.integrator : integrator, spp,
                                    comment);
            std::printf("%s/%s.xml: %llu triangles\n", outDir.c_str(), info.name,
                        (unsigned long long)scene.triangleCount());
        }
    } catch (const std::exception &e) {
        std::fprintf(stderr, "nori-genscene: %s\n", e.what());
        return 1;
    }
    return 0;
}
