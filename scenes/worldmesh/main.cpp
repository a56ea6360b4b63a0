/// \file main.cpp
/// \brief nori-worldmesh: writes one mesh of a Nori scene as an OBJ file in world space, with
/// its toWorld applied exactly as the renderer applies it.
//
//   nori-worldmesh SCENE.xml OUT.obj [--mesh N] [-a DIR]...
//
// What it is for: a stand-in for a mesh a scene names but that is missing. Nori's Ajax scenes
// (pa2, pa3, pa5) name `ajax.obj`, which is not distributed with them; the dragon scenes of
// scenes/ put the Stanford dragon in the bust's place through a toWorld. This tool bakes that
// placement into the vertices, so that the dragon, written as `ajax.obj` into a folder given
// to `nori -a`, lets Nori's own files render unmodified. Floats are written in their shortest
// round-trip form, so the renderer reads back the very vertices it would have computed (normals,
// which it normalises again on loading, may move by a unit in the last place).
// The file is written atomically (its folder created if missing): a failed run leaves no
// partial OBJ behind.

#include <app/cli_app.h>
#include <nori/atomic_file.h>
#include <nori/mesh.h>
#include <nori/parser.h>
#include <nori/resolver.h>
#include <nori/scene.h>
#include <charconv>
#include <filesystem>
#include <cstdio>

using namespace nori;

namespace {

/// OBJ text of \p mesh: positions, normals and texture coordinates if it has them, faces.
std::string objText(const Mesh &mesh, const std::string &comment) {
    std::string out = "# " + comment + "\n";
    out.reserve(mesh.positions().size() * 40 + mesh.faces().size() * 30);
    char buf[32];
    auto number = [&](float x) {
        out.push_back(' ');
        out.append(buf, std::to_chars(buf, buf + sizeof buf, x).ptr);
    };
    for (const Point3f &p : mesh.positions()) {
        out += "v";
        number(p.x()), number(p.y()), number(p.z());
        out += "\n";
    }
    for (const Normal3f &n : mesh.normals()) {
        out += "vn";
        number(n.x()), number(n.y()), number(n.z());
        out += "\n";
    }
    for (const Point2f &t : mesh.uvs()) {
        out += "vt";
        number(t.x()), number(t.y());
        out += "\n";
    }
    const bool normals = !mesh.normals().empty(), texcoords = !mesh.uvs().empty();
    for (const auto &f : mesh.faces()) {
        out += "f";
        for (uint32_t v : f) {
            const std::string i = std::to_string(v + 1);  // OBJ indices count from 1
            out += " " + i;
            if (texcoords || normals) out += "/" + (texcoords ? i : std::string());
            if (normals) out += "/" + i;
        }
        out += "\n";
    }
    return out;
}

} // namespace

int main(int argc, char **argv) {
    CliApp cli("nori-worldmesh", "Writes one mesh of a Nori scene as an OBJ file in world space (its toWorld "
                                 "applied as the renderer applies it): a stand-in for a mesh another scene names.");
    std::string scenePath, outPath;
    int index = 0;
    std::vector<std::string> searchPath;
    cli.app().add_option("scene", scenePath, "the Nori scene (XML)")->required()->option_text("SCENE.xml");
    cli.app().add_option("output", outPath, "the OBJ file to write")->required()->option_text("OUT.obj");
    cli.app()
        .add_option("--mesh", index, "which <mesh> of the scene, counting from 0 in file order (default 0)")
        ->check(integerIn(0, 1 << 30))
        ->option_text("N");
    cli.app()
        .add_option("-a,--search-path", searchPath, "look for files named in the scene in DIR too (repeatable)")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->allow_extra_args(false)
        ->option_text("DIR");
    if (std::optional<int> status = cli.parse(argc, argv)) return *status;
    try {
        for (const std::string &dir : searchPath) fileResolver().append(dir);
        // (No accel is needed here: brute force builds next to nothing.)
        SceneOverrides overrides;
        overrides.accelType = "brute";
        std::unique_ptr<Scene> scene = loadScene(scenePath, overrides);
        const auto &meshes = scene->meshes();
        if (size_t(index) >= meshes.size())
            throw NoriException("{}: --mesh {}: the scene has {} mesh{}", scenePath, index, meshes.size(),
                                meshes.size() == 1 ? "" : "es");
        const Mesh &mesh = *meshes[size_t(index)];
        // The output's folder is created if missing (as nori-genscene does for its own).
        const std::filesystem::path folder = std::filesystem::path(outPath).parent_path();
        std::error_code error;
        if (!folder.empty() && !std::filesystem::is_directory(folder) &&
            !std::filesystem::create_directories(folder, error))
            throw NoriException("{}: cannot create folder: {}", folder.string(),
                                error ? error.message() : "a file is in the way");
        AtomicFile::write(outPath, objText(mesh, fmt::format("nori-worldmesh: mesh {} of {} in world space", index, scenePath)));
        std::printf("nori-worldmesh: wrote %s (%zu vertices, %zu triangles)\n", outPath.c_str(), mesh.positions().size(),
                    mesh.faces().size());
    } catch (const std::exception &e) {
        std::fprintf(stderr, "nori-worldmesh: %s\n", oneLine(e.what()).c_str());
        return 1;
    }
    return 0;
}
