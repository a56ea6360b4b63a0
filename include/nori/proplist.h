/// \file proplist.h
/// \brief Typed name/value properties of a scene object, remembering where each was declared.
#pragma once

#include <nori/color.h>
#include <nori/transform.h>
#include <map>
#include <variant>
#include <vector>

namespace nori {

/// \brief The properties of one XML element. Getters mark a property as used, so that the
/// parser can reject properties no object asked for.
class PropertyList {
public:
    /// \brief Where the owning element was declared ("file:line"), used in messages.
    void setLocation(const std::string &location) { m_location = location; }
    const std::string &location() const { return m_location; }

    /// \brief Setters; \p where is "file:line" of the declaring element. Throws on duplicates.
    void setBoolean(const std::string &name, const bool &value, const std::string &where = "");
    void setInteger(const std::string &name, const int &value, const std::string &where = "");
    void setFloat(const std::string &name, const float &value, const std::string &where = "");
    void setString(const std::string &name, const std::string &value, const std::string &where = "");
    void setPoint(const std::string &name, const Point3f &value, const std::string &where = "");
    void setVector(const std::string &name, const Vector3f &value, const std::string &where = "");
    void setColor(const std::string &name, const Color3f &value, const std::string &where = "");
    void setTransform(const std::string &name, const Transform &value, const std::string &where = "");

    /// \brief Getters: without a default the property is required.
    bool getBoolean(const std::string &name) const;
    bool getBoolean(const std::string &name, const bool &defaultValue) const;
    int getInteger(const std::string &name) const;
    int getInteger(const std::string &name, const int &defaultValue) const;
    float getFloat(const std::string &name) const;
    float getFloat(const std::string &name, const float &defaultValue) const;
    std::string getString(const std::string &name) const;
    std::string getString(const std::string &name, const std::string &defaultValue) const;
    Point3f getPoint(const std::string &name) const;
    Point3f getPoint(const std::string &name, const Point3f &defaultValue) const;
    Vector3f getVector(const std::string &name) const;
    Vector3f getVector(const std::string &name, const Vector3f &defaultValue) const;
    Color3f getColor(const std::string &name) const;
    Color3f getColor(const std::string &name, const Color3f &defaultValue) const;
    Transform getTransform(const std::string &name) const;
    Transform getTransform(const std::string &name, const Transform &defaultValue) const;

    bool has(const std::string &name) const { return m_properties.count(name) != 0; }
    /// \brief Where property \p name was declared, or the element's location.
    std::string whereIs(const std::string &name) const;
    /// \brief Names of properties that no getter has read, in declaration order.
    std::vector<std::string> unusedProperties() const;
    /// \brief Copy every property of \p other into this list, replacing same-named ones.
    void overrideWith(const PropertyList &other);

    /// \brief Throw "where: message" (used by objects to reject a bad value).
    [[noreturn]] void fail(const std::string &name, const std::string &message) const;

private:
    using Value = std::variant<bool, int, float, std::string, Point3f, Color3f, Transform>;
    enum Kind { KBoolean, KInteger, KFloat, KString, KPoint, KVector, KColor, KTransform };
    struct Property {
        Kind kind;
        Value value;
        std::string where;
        int order = 0;
        mutable bool used = false;
    };
    void set(const std::string &name, Kind kind, Value value, const std::string &where);
    const Property *find(const std::string &name, Kind kind) const;
    static const char *kindName(Kind kind);

    std::map<std::string, Property> m_properties;
    std::string m_location;
    int m_nextOrder = 0;
};

} // namespace nori
