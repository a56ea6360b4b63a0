/// \file scene_geometry.cpp
/// \brief loadSceneGeometry: filter the XML with pugixml into a temporary file, parse that.
#include "scene_geometry.h"
#include <nori/parser.h>
#include <nori/resolver.h>
#include <pugixml.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <unistd.h>

namespace nori {

namespace {
/// Removes the temporary file and the resolver entry however the load ends.
struct TemporaryScene {
    std::string path;
    bool prepended = false;
    ~TemporaryScene() {
        if (!path.empty()) std::remove(path.c_str());
        if (prepended) fileResolver().popFront();
    }
};
} // namespace

std::unique_ptr<Scene> loadSceneGeometry(const std::string &path) {
    namespace fs = std::filesystem;
    pugi::xml_document doc;
    pugi::xml_parse_result parsed = doc.load_file(path.c_str());
    if (!parsed) throw NoriException("{}: cannot read the scene: {}", path, parsed.description());
    pugi::xml_node root = doc.child("scene");
    if (!root) throw NoriException("{}: the root element is not <scene>", path);

    pugi::xml_document out;
    pugi::xml_node scene = out.append_child("scene");
    for (pugi::xml_node node : root.children()) {
        std::string name = node.name();
        if (name == "camera") {
            scene.append_copy(node);
        } else if (name == "mesh") {
            pugi::xml_node mesh = scene.append_copy(node);
            for (pugi::xml_node child = mesh.first_child(); child;) {
                pugi::xml_node next = child.next_sibling();
                std::string kind = child.name();
                if (kind == "bsdf" || kind == "emitter") mesh.remove_child(child);
                child = next;
            }
        }
    }
    scene.append_child("integrator").append_attribute("type") = "normals";

    TemporaryScene tmp;
    std::string pattern = (fs::temp_directory_path() / "nori-geometry-XXXXXX.xml").string();
    int fd = mkstemps(pattern.data(), 4);
    if (fd < 0) throw NoriException("{}: cannot create a temporary file for the geometry", path);
    close(fd);
    tmp.path = pattern;
    if (!out.save_file(tmp.path.c_str())) throw NoriException("{}: cannot write {}", path, tmp.path);

    // Mesh names are relative to the original scene's folder, not the temporary file's.
    fs::path folder = fs::path(path).parent_path();
    fileResolver().prepend(folder.empty() ? std::string(".") : folder.string());
    tmp.prepended = true;
    SceneOverrides overrides;
    overrides.accelType = "brute";
    try {
        return loadScene(tmp.path, overrides);
    } catch (const NoriException &e) {
        // Name the file the user gave; the line numbers are those of the filtered copy.
        std::string message = e.what();
        size_t at = message.find(tmp.path);
        if (at != std::string::npos) message.replace(at, tmp.path.size(), path + " (geometry only)");
        throw NoriException(message);
    }
}

} // namespace nori
