/// \file proplist.cpp
/// \brief Typed name/value properties of a scene object, remembering where each was declared (implementation).
#include <nori/proplist.h>
#include <algorithm>

namespace nori {

const char *PropertyList::kindName(Kind kind) {
    static const char *names[] = {"boolean", "integer", "float", "string", "point", "vector", "color", "transform"};
    return names[kind];
}

void PropertyList::set(const std::string &name, Kind kind, Value value, const std::string &where) {
    if (m_properties.count(name))
        throw NoriException("{}: property '{}' is specified twice", where.empty() ? m_location : where, shown(name));
    m_properties[name] = Property{kind, std::move(value), where.empty() ? m_location : where, m_nextOrder++};
}

const PropertyList::Property *PropertyList::find(const std::string &name, Kind kind) const {
    auto it = m_properties.find(name);
    if (it == m_properties.end()) return nullptr;
    const Property &p = it->second;
    if (p.kind != kind)
        throw NoriException("{}: property '{}' has the wrong type: expected {}, found {}", p.where, shown(name),
                            kindName(kind), kindName(p.kind));
    p.used = true;
    return &p;
}

std::string PropertyList::whereIs(const std::string &name) const {
    auto it = m_properties.find(name);
    return it == m_properties.end() ? m_location : it->second.where;
}

void PropertyList::fail(const std::string &name, const std::string &message) const {
    throw NoriException("{}: {}", whereIs(name), message);
}

std::vector<std::string> PropertyList::unusedProperties() const {
    std::vector<std::pair<int, std::string>> unused;
    for (const auto &entry : m_properties)
        if (!entry.second.used) unused.emplace_back(entry.second.order, entry.first);
    std::sort(unused.begin(), unused.end());
    std::vector<std::string> names;
    for (auto &u : unused) names.push_back(u.second);
    return names;
}

void PropertyList::overrideWith(const PropertyList &other) {
    for (const auto &entry : other.m_properties) {
        Property p = entry.second;
        p.order = m_nextOrder++;
        p.used = false;
        m_properties[entry.first] = p;
    }
}

// One setter/getter pair per kind; the getters without default report a missing property.
#define NORI_PROPERTY_ACCESSORS(Type, Name, KindTag, Stored)                                             \
    void PropertyList::set##Name(const std::string &name, const Type &value, const std::string &where) { \
        set(name, KindTag, Value(Stored(value)), where);                                                 \
    }                                                                                                    \
    Type PropertyList::get##Name(const std::string &name) const {                                        \
        const Property *p = find(name, KindTag);                                                         \
        if (!p) throw NoriException("{}: missing required {} property '{}'", m_location, kindName(KindTag), name); \
        return std::get<Stored>(p->value);                                                               \
    }                                                                                                    \
    Type PropertyList::get##Name(const std::string &name, const Type &defaultValue) const {              \
        const Property *p = find(name, KindTag);                                                         \
        return p ? Type(std::get<Stored>(p->value)) : defaultValue;                                      \
    }

NORI_PROPERTY_ACCESSORS(bool, Boolean, KBoolean, bool)
NORI_PROPERTY_ACCESSORS(int, Integer, KInteger, int)
NORI_PROPERTY_ACCESSORS(float, Float, KFloat, float)
NORI_PROPERTY_ACCESSORS(std::string, String, KString, std::string)
NORI_PROPERTY_ACCESSORS(Point3f, Point, KPoint, Point3f)
NORI_PROPERTY_ACCESSORS(Vector3f, Vector, KVector, Point3f)
NORI_PROPERTY_ACCESSORS(Color3f, Color, KColor, Color3f)
NORI_PROPERTY_ACCESSORS(Transform, Transform, KTransform, Transform)

#undef NORI_PROPERTY_ACCESSORS

} // namespace nori
