/// \file registry.cpp
/// \brief The table of shapes, parameter checks and the camera factory.
#include "scene_generator.h"
#include "shape_generators.h"
#include <nori/transform.h>
#include <cmath>

namespace nori::gen {

const std::vector<ShapeInfo> &shapes() {
    static const std::vector<ShapeInfo> table = {
        {"city", "10k axis-aligned boxes on a ground quad, 120 x 8 x 120", 120002, 14, &generateCity},
        {"grass", "80k thin blades (long thin triangles) on a ground quad", 160002, 4, &generateGrass},
        {"heightfield", "terrain strip 1000x longer than tall, grazing view", 128000, 64, &generateHeightfield},
        {"sphere", "noise-displaced sphere (a rock)", 100000, 12, &generateDisplacedSphere},
        {"room", "big walls, tables, small objects, camera inside", 140000, 5000, &generateRoom},
        {"wide", "plain 1000x wider than tall with clusters of rocks", 100000, 1000, &generateWide},
        {"tabletop", "tiny objects on a table on a huge ground quad", 25000, 2000, &generateTabletop},
        {"stadium", "teapot in a stadium: small detailed object in a huge bowl", 100000, 5000, &generateStadium},
        {"coplanar", "overlapping coplanar faces on the split planes", 20000, 5000, &generateCoplanar},
        {"forest", "trees of mixed sizes (trunks, branches, leaf clusters) on terrain", 120000, 3000, &generateForest},
        {"office", "many small rooms of thin walls with doors, camera down a corridor", 120000, 3000, &generateOffice},
        {"towers", "skyscrapers up to 900 high on a plaza 120 across, portrait view", 120000, 1000, &generateTowers},
        {"clutter", "stones from 2 cm to 40 m on a mountainside", 120000, 2000, &generateClutter},
        {"hair", "head with thousands of long thin strands falling over it", 120000, 2000, &generateHair},
        {"sparse", "asteroid field: rocks far apart, cut by a tilted ring of huge triangles", 120000, 2000, &generateSparse},
        {"park", "crossed-card trees on a lawn under a sky dome with polar fans, camera inside", 120000, 2000, &generatePark},
        {"speck", "rock 1 across on the diagonal of a ground quad 100,000 across", 40000, 14, &generateSpeck},
    };
    return table;
}

const ShapeInfo *findShape(const std::string &name) {
    for (const ShapeInfo &s : shapes())
        if (name == s.name) return &s;
    return nullptr;
}

std::string shapeList() {
    std::string list;
    for (const ShapeInfo &s : shapes()) list += (list.empty() ? "" : ", ") + std::string(s.name);
    return list;
}

void place(GeneratedScene &scene, const Placement &placement) {
    const Transform motion = Transform::translate(placement.offset) * Transform::rotate(placement.axis, placement.degrees);
    for (Point3f &p : scene.mesh.positions) p = motion.applyPoint(p);
    for (Normal3f &n : scene.mesh.normals) n = motion.applyNormal(n).normalized();
    scene.camera.origin = motion.applyPoint(scene.camera.origin);
    scene.camera.target = motion.applyPoint(scene.camera.target);
    scene.camera.up = motion.applyVector(scene.camera.up);
}

GeneratedScene generateScene(const std::string &name, const GenParams &params) {
    const ShapeInfo *info = findShape(name);
    if (!info) throw NoriException("unknown scene shape '{}' (expected one of: {})", name, shapeList());
    const uint64_t maxTriangles = 50000000;
    GenParams p = params;
    if (p.triangles == 0) p.triangles = info->defaultTriangles;
    if (p.triangles < info->minTriangles || p.triangles > maxTriangles)
        throw NoriException("shape '{}' needs between {} and {} triangles, got {}", name, info->minTriangles,
                            maxTriangles, p.triangles);
    const Placement &pl = p.placement;
    if (pl.degrees != 0.0f && (!pl.axis.allFinite() || pl.axis.norm() == 0.0f || !std::isfinite(pl.degrees)))
        throw NoriException("placement of shape '{}': a rotation needs a finite nonzero axis and a finite angle", name);
    if (!pl.offset.allFinite())
        throw NoriException("placement of shape '{}': an offset needs finite coordinates", name);
    GeneratedScene scene = info->generate(p);
    if (!p.placement.isIdentity()) place(scene, p.placement);
    return scene;
}

std::unique_ptr<Camera> makeCamera(const GenCamera &c) {
    PropertyList props;
    props.setLocation("<generated camera>");
    props.setInteger("width", c.width);
    props.setInteger("height", c.height);
    props.setFloat("fov", c.fov);
    props.setFloat("nearClip", c.nearClip);
    props.setFloat("farClip", c.farClip);
    props.setTransform("toWorld", Transform::lookAt(c.origin, c.target, c.up));
    std::unique_ptr<NoriObject> object = NoriObjectFactory::createInstance(NoriObject::ECamera, "perspective", props);
    object->activate();
    return std::unique_ptr<Camera>(static_cast<Camera *>(object.release()));
}

} // namespace nori::gen
