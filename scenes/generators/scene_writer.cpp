/// \file scene_writer.cpp
/// \brief SceneWriter: OBJ and XML text, written through temporary files and rename().
#include "scene_writer.h"
#include <fmt/format.h>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <unistd.h>

namespace nori::gen {

std::string SceneWriter::objText(const MeshData &mesh, const std::string &comment) {
    fmt::memory_buffer out;
    fmt::format_to(std::back_inserter(out), "# {}\n# {} vertices, {} triangles\n", comment, mesh.positions.size(),
                   mesh.faces.size());
    for (const Point3f &p : mesh.positions)
        fmt::format_to(std::back_inserter(out), "v {} {} {}\n", p.x(), p.y(), p.z());
    for (const auto &f : mesh.faces)
        fmt::format_to(std::back_inserter(out), "f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
    return fmt::to_string(out);
}

namespace {
std::string vec(const Vector3f &v) { return fmt::format("{}, {}, {}", v.x(), v.y(), v.z()); }
} // namespace

std::string SceneWriter::xmlText(const GeneratedScene &s, const std::string &objName, const std::string &integrator,
                                 int spp, const std::string &comment) {
    std::string integratorXml =
        integrator == "ao" ? fmt::format("\t<integrator type=\"ao\">\n\t\t<float name=\"length\" value=\"{}\"/>\n"
                                         "\t</integrator>\n",
                                         s.aoLength)
                           : fmt::format("\t<integrator type=\"{}\"/>\n", integrator);
    const GenCamera &c = s.camera;
    return fmt::format(
        "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
        "<!-- {}\n     {}: {} triangles -->\n"
        "<scene>\n"
        "\t<sampler type=\"independent\">\n\t\t<integer name=\"sampleCount\" value=\"{}\"/>\n\t</sampler>\n"
        "{}"
        "\t<mesh type=\"obj\">\n\t\t<string name=\"filename\" value=\"{}\"/>\n"
        "\t\t<bsdf type=\"diffuse\">\n\t\t\t<color name=\"albedo\" value=\"0.7, 0.7, 0.7\"/>\n\t\t</bsdf>\n"
        "\t</mesh>\n"
        "\t<camera type=\"perspective\">\n"
        "\t\t<transform name=\"toWorld\">\n\t\t\t<lookat origin=\"{}\" target=\"{}\" up=\"{}\"/>\n\t\t</transform>\n"
        "\t\t<float name=\"fov\" value=\"{}\"/>\n"
        "\t\t<float name=\"nearClip\" value=\"{}\"/>\n\t\t<float name=\"farClip\" value=\"{}\"/>\n"
        "\t\t<integer name=\"width\" value=\"{}\"/>\n\t\t<integer name=\"height\" value=\"{}\"/>\n"
        "\t</camera>\n"
        "</scene>\n",
        comment, s.description, s.triangleCount(), spp, integratorXml, objName, vec(c.origin), vec(c.target), vec(c.up),
        c.fov, c.nearClip, c.farClip, c.width, c.height);
}

namespace {
/// Write \p content to a fresh temporary file beside \p path; returns its name.
std::string writeTemporary(const std::string &path, const std::string &content) {
    std::string tmp = fmt::format("{}.tmp.{}", path, long(getpid()));
    FILE *f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw NoriException("{}: cannot write: {}", tmp, std::strerror(errno));
    bool ok = std::fwrite(content.data(), 1, content.size(), f) == content.size() && std::fflush(f) == 0 &&
              fsync(fileno(f)) == 0;
    int err = errno;
    ok = std::fclose(f) == 0 && ok;
    if (!ok) {
        std::remove(tmp.c_str());
        throw NoriException("{}: cannot write: {}", path, std::strerror(err ? err : EIO));
    }
    return tmp;
}
} // namespace

void SceneWriter::write(const GeneratedScene &scene, const std::string &outDir, const std::string &name,
                        const std::string &integrator, int spp, const std::string &comment) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(outDir, ec);
    if (ec || !fs::is_directory(outDir)) throw NoriException("{}: cannot create folder: {}", outDir, ec.message());
    std::string objPath = (fs::path(outDir) / (name + ".obj")).string();
    std::string xmlPath = (fs::path(outDir) / (name + ".xml")).string();
    std::string objTmp = writeTemporary(objPath, objText(scene.mesh, comment));
    std::string xmlTmp;
    try {
        xmlTmp = writeTemporary(xmlPath, xmlText(scene, name + ".obj", integrator, spp, comment));
    } catch (...) {
        std::remove(objTmp.c_str());
        throw;
    }
    // The mesh first: a scene file never names a mesh that is not there yet.
    if (std::rename(objTmp.c_str(), objPath.c_str()) != 0) {
        int err = errno;
        std::remove(objTmp.c_str());
        std::remove(xmlTmp.c_str());
        throw NoriException("{}: cannot write: {}", objPath, std::strerror(err));
    }
    if (std::rename(xmlTmp.c_str(), xmlPath.c_str()) != 0) {
        int err = errno;
        std::remove(xmlTmp.c_str());
        throw NoriException("{}: cannot write: {}", xmlPath, std::strerror(err));
    }
}

} // namespace nori::gen
