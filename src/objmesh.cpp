/// Mesh loaded from a Wavefront OBJ file (Nori's `obj`).
#include <nori/mesh.h>
#include <nori/objloader.h>
#include <nori/resolver.h>

namespace nori {

class WavefrontOBJ : public Mesh {
public:
    explicit WavefrontOBJ(const PropertyList &props) {
        std::string filename = props.getString("filename");
        Transform toWorld = props.getTransform("toWorld", Transform());
        std::string path = fileResolver().resolve(filename);
        MeshData data;
        try {
            data = loadObjFile(path);
        } catch (const NoriException &e) {
            // The loader names the OBJ file and line; say which scene element asked for it.
            throw NoriException("{} (mesh declared at {})", e.what(), props.whereIs("filename"));
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
