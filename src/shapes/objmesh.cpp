/// \file objmesh.cpp
/// \brief Mesh loaded from a Wavefront OBJ file (Nori's `obj`).
#include <nori/mesh.h>
#include <nori/objloader.h>
#include <nori/resolver.h>

namespace nori {

class WavefrontOBJ : public Mesh {
public:
    explicit WavefrontOBJ(const PropertyList &props) {
        std::string filename = props.getString("filename");
        if (filename.empty()) props.fail("filename", "the mesh filename is empty");
        Transform toWorld = props.getTransform("toWorld", Transform());
        std::string path = fileResolver().resolve(filename);
        MeshData data;
        try {
            data = loadObjFile(path);
        } catch (const NoriException &e) {
            // A parse error names the OBJ file and line: add which scene element asked for it.
            // An I/O error ("PATH: cannot open: ...") has no line: lead with the scene's line.
            std::string message = e.what();
            bool hasLine = message.size() > path.size() + 1 && message.compare(0, path.size(), path) == 0 &&
                           message[path.size()] == ':' && std::isdigit((unsigned char)message[path.size() + 1]);
            if (hasLine) throw NoriException("{} (mesh declared at {})", message, props.whereIs("filename"));
            throw NoriException("{}: {}", props.whereIs("filename"), message);
        }
        for (Point3f &p : data.positions) p = toWorld.applyPoint(p);
        for (Normal3f &n : data.normals) {
            n = toWorld.applyNormal(n);
            float len = n.norm();
            if (len > 0.0f) n /= len;
        }
        m_name = filename;
        setData(std::move(data));
        for (const Point3f &p : m_data.positions)
            if (!p.allFinite()) props.fail("toWorld", "toWorld maps a vertex of '" + filename + "' to infinity");
    }
};

NORI_REGISTER_CLASS(WavefrontOBJ, "obj", EMesh);

} // namespace nori
