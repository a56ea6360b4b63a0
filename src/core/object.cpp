/// \file object.cpp
/// \brief Base class of every scene object, and the registry that creates them by type name (implementation).
#include <nori/object.h>
#include <algorithm>
#include <fmt/ranges.h>
#include <map>

namespace nori {

void NoriObject::addChild(std::unique_ptr<NoriObject> child) {
    throw NoriException("{}: a {} cannot contain a {}", child->location(), classTypeName(getClassType()),
                        classTypeName(child->getClassType()));
}

const char *NoriObject::classTypeName(EClassType type) {
    static const char *names[] = {"scene", "mesh", "bsdf", "camera", "sampler", "integrator", "rfilter", "accel", "emitter", "test"};
    return type < EClassTypeCount ? names[type] : "unknown";
}

namespace {
// Function-local static: registration runs during static initialisation of other files.
std::map<std::pair<int, std::string>, NoriObjectFactory::Constructor> &registry() {
    static std::map<std::pair<int, std::string>, NoriObjectFactory::Constructor> instance;
    return instance;
}
} // namespace

void NoriObjectFactory::registerClass(NoriObject::EClassType type, const std::string &name,
                                      const Constructor &ctor) {
    registry()[{int(type), name}] = ctor;
}

bool NoriObjectFactory::isRegistered(NoriObject::EClassType type, const std::string &name) {
    return registry().count({int(type), name}) != 0;
}

std::vector<std::string> NoriObjectFactory::registeredNames(NoriObject::EClassType type) {
    std::vector<std::string> names;
    for (const auto &entry : registry())
        if (entry.first.first == int(type)) names.push_back(entry.first.second);
    return names;
}

std::unique_ptr<NoriObject> NoriObjectFactory::createInstance(NoriObject::EClassType type, const std::string &name,
                                                              const PropertyList &props) {
    auto it = registry().find({int(type), name});
    if (it == registry().end()) {
        std::vector<std::string> known = registeredNames(type);
        throw NoriException("{}: unknown {} type '{}' (known: {})", props.location(), NoriObject::classTypeName(type),
                            shown(name), known.empty() ? std::string("none") : fmt::format("{}", fmt::join(known, ", ")));
    }
    std::unique_ptr<NoriObject> object = it->second(props);
    object->setLocation(props.location());
    return object;
}

} // namespace nori
