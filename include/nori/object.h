/// \file object.h
/// \brief Base class of every scene object, and the registry that creates them by type name.
#pragma once

#include <nori/proplist.h>
#include <functional>
#include <memory>

namespace nori {

/// \brief A node of the scene description (mesh, camera, integrator, ...).
class NoriObject {
public:
    /// \brief The XML element an object belongs to.
    enum EClassType { EScene = 0, EMesh, EBSDF, ECamera, ESampler, EIntegrator,
                      EReconstructionFilter, EAccel, EEmitter, ETest, EClassTypeCount };

    virtual ~NoriObject() = default;
    /// \brief Which XML element this object is.
    virtual EClassType getClassType() const = 0;
    /// \brief Take ownership of a nested object. The default rejects every child.
    virtual void addChild(std::unique_ptr<NoriObject> child);
    /// \brief Called once all children are attached.
    virtual void activate() {}
    /// \brief Human-readable summary for debugging.
    virtual std::string toString() const = 0;

    /// \brief Where the object was declared ("file:line"), for error messages.
    const std::string &location() const { return m_location; }
    void setLocation(const std::string &location) { m_location = location; }

    /// \brief XML element name of a class type ("mesh", "bsdf", ...).
    static const char *classTypeName(EClassType type);

private:
    std::string m_location;
};

/// \brief Registry of constructors keyed by the XML `type` attribute.
class NoriObjectFactory {
public:
    using Constructor = std::function<std::unique_ptr<NoriObject>(const PropertyList &)>;

    /// \brief Register a constructor (called by NORI_REGISTER_CLASS at start-up).
    static void registerClass(NoriObject::EClassType type, const std::string &name, const Constructor &ctor);
    /// \brief Create an instance; throws "unknown type" if \p name is not registered for \p type.
    static std::unique_ptr<NoriObject> createInstance(NoriObject::EClassType type, const std::string &name,
                                                      const PropertyList &props);
    /// \brief Is \p name registered for \p type?
    static bool isRegistered(NoriObject::EClassType type, const std::string &name);
    /// \brief The names registered for \p type, sorted (for --help and error messages).
    static std::vector<std::string> registeredNames(NoriObject::EClassType type);
};

} // namespace nori

/// \brief Register class \p cls under the XML type name \p name.
#define NORI_REGISTER_CLASS(cls, name, classType)                                          \
    static const bool cls##_registered_ = [] {                                             \
        ::nori::NoriObjectFactory::registerClass(                                          \
            ::nori::NoriObject::classType, name,                                            \
            [](const ::nori::PropertyList &props) -> std::unique_ptr<::nori::NoriObject> { \
                return std::make_unique<cls>(props);                                       \
            });                                                                            \
        return true;                                                                       \
    }()
