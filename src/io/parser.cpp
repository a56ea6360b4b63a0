/// \file parser.cpp
/// \brief Loads Nori's XML scene format (implementation).
#include "input_file.h"
#include <nori/parser.h>
#include <nori/resolver.h>
#include <nori/scene.h>
#include <algorithm>
#include <cctype>
#include <cstring>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <map>
#include <pugixml.hpp>
#include <set>
#include <sstream>
#include <vector>

namespace nori {

namespace {

/// The XML elements of the format: objects, properties and transform operations.
enum class Tag { Object, Boolean, Integer, Float, String, Point, Vector, Color, Transform,
                 Translate, Scale, Rotate, LookAt, Matrix, Unknown };

struct TagInfo {
    Tag tag;
    NoriObject::EClassType classType;  // for Tag::Object
};

TagInfo classify(const std::string &name) {
    static const std::map<std::string, TagInfo> tags = {
        {"scene", {Tag::Object, NoriObject::EScene}},
        {"mesh", {Tag::Object, NoriObject::EMesh}},
        {"bsdf", {Tag::Object, NoriObject::EBSDF}},
        {"camera", {Tag::Object, NoriObject::ECamera}},
        {"sampler", {Tag::Object, NoriObject::ESampler}},
        {"integrator", {Tag::Object, NoriObject::EIntegrator}},
        {"rfilter", {Tag::Object, NoriObject::EReconstructionFilter}},
        {"accel", {Tag::Object, NoriObject::EAccel}},
        {"emitter", {Tag::Object, NoriObject::EEmitter}},
        {"test", {Tag::Object, NoriObject::ETest}},
        {"boolean", {Tag::Boolean, NoriObject::EScene}},
        {"integer", {Tag::Integer, NoriObject::EScene}},
        {"float", {Tag::Float, NoriObject::EScene}},
        {"string", {Tag::String, NoriObject::EScene}},
        {"point", {Tag::Point, NoriObject::EScene}},
        {"vector", {Tag::Vector, NoriObject::EScene}},
        {"color", {Tag::Color, NoriObject::EScene}},
        {"transform", {Tag::Transform, NoriObject::EScene}},
        {"translate", {Tag::Translate, NoriObject::EScene}},
        {"scale", {Tag::Scale, NoriObject::EScene}},
        {"rotate", {Tag::Rotate, NoriObject::EScene}},
        {"lookat", {Tag::LookAt, NoriObject::EScene}},
        {"matrix", {Tag::Matrix, NoriObject::EScene}},
    };
    auto it = tags.find(name);
    return it == tags.end() ? TagInfo{Tag::Unknown, NoriObject::EScene} : it->second;
}

/// An element's start tag: its name and the byte offset of its '<'.
struct StartTag {
    std::string name;
    size_t offset;
};

/// The elements still open before byte \p end of \p text, outermost first. Used only to explain
/// a start/end tag mismatch that pugixml has already found (pugixml does not say which element
/// was left open): a plain scan of tags that skips comments, processing instructions, CDATA and
/// DOCTYPE, and ignores '>' inside quoted attribute values.
std::vector<StartTag> openElements(const std::string &text, size_t end) {
    auto skipPast = [&text](size_t from, const std::string &terminator) {
        size_t k = text.find(terminator, from);
        return k == std::string::npos ? text.size() : k + terminator.size();
    };
    std::vector<StartTag> open;
    size_t i = 0;
    while ((i = text.find('<', i)) < end) {
        if (text.compare(i, 4, "<!--") == 0) {
            i = skipPast(i + 4, "-->");
        } else if (text.compare(i, 9, "<![CDATA[") == 0) {
            i = skipPast(i + 9, "]]>");
        } else if (text.compare(i, 2, "<?") == 0) {
            i = skipPast(i + 2, "?>");
        } else if (text.compare(i, 2, "<!") == 0) {
            i = skipPast(i + 2, ">");
        } else if (text.compare(i, 2, "</") == 0) {
            if (!open.empty()) open.pop_back();
            i = skipPast(i + 2, ">");
        } else {
            size_t nameEnd = i + 1;
            while (nameEnd < text.size() && !std::isspace((unsigned char) text[nameEnd]) && text[nameEnd] != '>' &&
                   text[nameEnd] != '/')
                ++nameEnd;
            size_t k = nameEnd;
            for (char quote = 0; k < text.size(); ++k) {
                if (quote) {
                    if (text[k] == quote) quote = 0;
                } else if (text[k] == '"' || text[k] == '\'') {
                    quote = text[k];
                } else if (text[k] == '>') {
                    break;
                }
            }
            if (k >= text.size() || text[k - 1] != '/') open.push_back({text.substr(i + 1, nameEnd - i - 1), i});
            i = k + 1;
        }
    }
    return open;
}

bool isTransformOperation(Tag tag) {
    return tag == Tag::Translate || tag == Tag::Scale || tag == Tag::Rotate || tag == Tag::LookAt ||
           tag == Tag::Matrix;
}

/// Parses one document; knows the file's text to turn byte offsets into line:column.
class SceneParser {
public:
    SceneParser(std::string path, std::string text, const SceneOverrides &overrides)
        : m_path(std::move(path)), m_text(std::move(text)), m_overrides(overrides) {
        // A UTF-8 byte order mark is no character: drop it so that columns on line 1 stay right.
        if (m_text.compare(0, 3, "\xEF\xBB\xBF") == 0) m_text.erase(0, 3);
        m_lineStarts.push_back(0);
        for (size_t i = 0; i < m_text.size(); ++i)
            if (m_text[i] == '\n') m_lineStarts.push_back(i + 1);
    }

    std::unique_ptr<NoriObject> parse() {
        pugi::xml_document doc;
        pugi::xml_node root = documentElement(doc);
        PropertyList unusedProps;
        Transform unusedTransform;
        std::unique_ptr<NoriObject> object = parseElement(root, Tag::Unknown, unusedProps, unusedTransform);
        if (!object) throw NoriException("{}: the root element must be an object such as <scene>", where(root));
        return object;
    }

    /// The document's single top-level element (XML errors throw), before any object is built.
    pugi::xml_node documentElement(pugi::xml_document &doc) {
        // UTF-16 and UTF-32 (with or without a byte order mark, XML 1.0 appendix F) would only
        // be called binary below: name the encoding instead.
        static const std::pair<const char *, std::string> encodings[] = {
            {"UTF-32", std::string("\x00\x00\xFE\xFF", 4)}, {"UTF-32", std::string("\xFF\xFE\x00\x00", 4)},
            {"UTF-32", std::string("\x00\x00\x00<", 4)},     {"UTF-32", std::string("<\x00\x00\x00", 4)},
            {"UTF-16", std::string("\xFE\xFF")},             {"UTF-16", std::string("\xFF\xFE")},
            {"UTF-16", std::string("\x00<", 2)},               {"UTF-16", std::string("<\x00", 2)}};
        for (const auto &[name, start] : encodings)
            if (m_text.compare(0, start.size(), start) == 0)
                throw NoriException("{}:1:1: the file is {} encoded; scene files must be UTF-8 (save it as UTF-8)",
                                    m_path, name);
        // A NUL byte never occurs in XML text: say "binary" instead of a confusing parse error.
        size_t nul = m_text.find('\0');
        if (nul != std::string::npos)
            throw NoriException("{}: binary data (a NUL byte), not an XML scene file", where(ptrdiff_t(nul)));
        pugi::xml_parse_result result = doc.load_buffer(m_text.data(), m_text.size(), pugi::parse_default);
        // pugixml reports "no document element" at the end of the file; line 1 is more useful.
        if (result.status == pugi::status_no_document_element)
            throw NoriException("{}:1: not an XML scene file (no XML element found)", m_path);
        if (result.status == pugi::status_end_element_mismatch) explainMismatch(size_t(result.offset));
        if (!result) throw NoriException("{}: XML error: {}", where(result.offset), result.description());
        pugi::xml_node root = doc.document_element();
        if (!root) throw NoriException("{}:1: the file has no XML element", m_path);
        // pugixml accepts several top-level elements; a scene file has exactly one.
        for (pugi::xml_node extra = root.next_sibling(); extra; extra = extra.next_sibling())
            if (extra.type() == pugi::node_element)
                fail(extra, fmt::format("a second top-level element <{}> (a scene file has one root)", extra.name()));
        return root;
    }

private:
    /// pugixml reports a mismatch where it notices it (a wrong end tag, or the end of the
    /// file) without naming the element left open; name it, with the line it opens on.
    void explainMismatch(size_t offset) const {
        size_t tag = m_text.rfind('<', std::min(offset, m_text.size() - 1));
        if (tag != std::string::npos && m_text.compare(tag, 2, "</") == 0) {
            std::vector<StartTag> open = openElements(m_text, tag);
            size_t nameEnd = std::min(m_text.find_first_of(" \t\r\n>", tag + 2), m_text.size());
            std::string endName = m_text.substr(tag + 2, nameEnd - tag - 2);
            if (!open.empty() && open.back().name != endName)
                throw NoriException("{}: XML error: </{}> does not close <{}> (opened on line {})", where(ptrdiff_t(tag)),
                                    endName, open.back().name, lineOf(open.back().offset));
        }
        // Otherwise pugixml ran into the end of the file with elements still open.
        std::vector<StartTag> open = openElements(m_text, m_text.size());
        if (!open.empty())
            throw NoriException("{}: XML error: <{}> is never closed (the file ends first)",
                                where(ptrdiff_t(open.back().offset)), open.back().name);
    }

    size_t lineOf(size_t offset) const {
        return size_t(std::upper_bound(m_lineStarts.begin(), m_lineStarts.end(), offset) - m_lineStarts.begin());
    }

    std::string where(ptrdiff_t offset) const {
        size_t line = lineOf(size_t(offset));
        size_t col = size_t(offset) - m_lineStarts[line - 1] + 1;
        return fmt::format("{}:{}:{}", m_path, line, col);
    }
    std::string where(const pugi::xml_node &node) const { return where(node.offset_debug()); }

    [[noreturn]] void fail(const pugi::xml_node &node, const std::string &message) const {
        throw NoriException("{}: {}", where(node), message);
    }

    void checkAttributes(const pugi::xml_node &node, std::initializer_list<const char *> allowed,
                         std::initializer_list<const char *> required) const {
        // XML forbids an attribute twice in one tag (pugixml keeps both): which value was meant?
        for (pugi::xml_attribute attr = node.first_attribute(); attr; attr = attr.next_attribute())
            for (pugi::xml_attribute later = attr.next_attribute(); later; later = later.next_attribute())
                if (std::strcmp(attr.name(), later.name()) == 0)
                    fail(node, fmt::format("attribute '{}' given twice in <{}>", shown(attr.name()), node.name()));
        for (const pugi::xml_attribute &attr : node.attributes()) {
            bool ok = std::any_of(allowed.begin(), allowed.end(),
                                  [&](const char *a) { return std::string(a) == attr.name(); });
            if (!ok) fail(node, fmt::format("unexpected attribute '{}' in <{}>", shown(attr.name()), node.name()));
        }
        for (const char *r : required)
            if (!node.attribute(r)) fail(node, fmt::format("<{}> needs the attribute '{}'", node.name(), r));
    }

    std::string attr(const pugi::xml_node &node, const char *name) const { return node.attribute(name).value(); }

    float parseFloat(const pugi::xml_node &node, const std::string &text, const char *what) const {
        const char *begin = text.data(), *end = text.data() + text.size();
        while (begin < end && std::isspace((unsigned char)*begin)) ++begin;
        while (end > begin && std::isspace((unsigned char)end[-1])) --end;
        if (begin < end && *begin == '+') ++begin;
        float value = 0.0f;
        auto [ptr, ec] = std::from_chars(begin, end, value);
        if (ec == std::errc::result_out_of_range && ptr == end)
            fail(node, fmt::format("{} '{}' is out of the float range", what, shown(text)));
        if (ec != std::errc() || ptr != end || begin == end)
            fail(node, fmt::format("{} '{}' is not a number", what, shown(text)));
        if (!std::isfinite(value)) fail(node, fmt::format("{} '{}' is not a finite number", what, shown(text)));
        return value;
    }

    /// Components of a vector or matrix value, separated by commas and/or whitespace.
    static std::vector<std::string> splitComponents(const std::string &text) {
        std::vector<std::string> tokens;
        std::string token;
        for (char c : text) {
            if (c == ',' || std::isspace((unsigned char)c)) {
                if (!token.empty()) tokens.push_back(token);
                token.clear();
            } else {
                token += c;
            }
        }
        if (!token.empty()) tokens.push_back(token);
        return tokens;
    }

    /// "x, y, z" (commas and/or whitespace); a single value is repeated if \p allowScalar.
    Vector3f parseVector(const pugi::xml_node &node, const std::string &text, const char *what,
                         bool allowScalar = false) const {
        std::vector<std::string> tokens = splitComponents(text);
        if (allowScalar && tokens.size() == 1) return Vector3f::Constant(parseFloat(node, tokens[0], what));
        if (tokens.size() != 3)
            fail(node, fmt::format("{} '{}' must have 3 components, found {}", what, shown(text), tokens.size()));
        return Vector3f(parseFloat(node, tokens[0], what), parseFloat(node, tokens[1], what),
                        parseFloat(node, tokens[2], what));
    }

    int parseInteger(const pugi::xml_node &node, const std::string &text) const {
        const char *begin = text.data(), *end = text.data() + text.size();
        while (begin < end && std::isspace((unsigned char)*begin)) ++begin;
        while (end > begin && std::isspace((unsigned char)end[-1])) --end;
        if (begin < end && *begin == '+') ++begin;
        long long value = 0;
        auto [ptr, ec] = std::from_chars(begin, end, value);
        if (ec == std::errc::result_out_of_range || (ec == std::errc() && ptr == end && begin != end &&
                                                     (value > INT32_MAX || value < INT32_MIN)))
            fail(node, fmt::format("integer '{}' is out of range", shown(text)));
        if (ec != std::errc() || ptr != end || begin == end)
            fail(node, fmt::format("'{}' is not an integer", shown(text)));
        return int(value);
    }

    Transform parseTransformOperation(const pugi::xml_node &node, Tag tag) const {
        try {
            switch (tag) {
            case Tag::Translate:
                checkAttributes(node, {"value"}, {"value"});
                return Transform::translate(parseVector(node, attr(node, "value"), "translation"));
            case Tag::Scale:
                checkAttributes(node, {"value"}, {"value"});
                return Transform::scale(parseVector(node, attr(node, "value"), "scale", true));
            case Tag::Rotate:
                checkAttributes(node, {"axis", "angle"}, {"axis", "angle"});
                return Transform::rotate(parseVector(node, attr(node, "axis"), "rotation axis"),
                                         parseFloat(node, attr(node, "angle"), "rotation angle"));
            case Tag::LookAt: {
                checkAttributes(node, {"origin", "target", "up"}, {"origin", "target"});
                Vector3f up = node.attribute("up") ? parseVector(node, attr(node, "up"), "up vector")
                                                   : Vector3f(0, 1, 0);
                return Transform::lookAt(parseVector(node, attr(node, "origin"), "origin"),
                                         parseVector(node, attr(node, "target"), "target"), up);
            }
            case Tag::Matrix: {
                checkAttributes(node, {"value"}, {"value"});
                std::vector<std::string> tokens = splitComponents(attr(node, "value"));
                if (tokens.size() != 16)
                    fail(node, fmt::format("matrix needs 16 values (row-major), found {}", tokens.size()));
                Matrix4f m;
                for (int i = 0; i < 16; ++i) m(i / 4, i % 4) = parseFloat(node, tokens[i], "matrix entry");
                return Transform(m);
            }
            default:
                break;
            }
        } catch (const NoriException &e) {
            // Transform's own checks know no location: add it.
            std::string message = e.what();
            if (message.rfind(m_path, 0) == 0) throw;
            fail(node, message);
        }
        fail(node, "not a transform operation");
    }

    /// Parses \p node; returns the created object for object elements, nullptr otherwise.
    /// Properties go into \p parentProps; transform operations compose into \p parentTransform.
    std::unique_ptr<NoriObject> parseElement(const pugi::xml_node &node, Tag parentTag, PropertyList &parentProps,
                                             Transform &parentTransform) {
        if (node.type() != pugi::node_element) return nullptr;
        const std::string name = node.name();
        TagInfo info = classify(name);
        if (info.tag == Tag::Unknown) fail(node, fmt::format("unknown element <{}>", shown(name)));

        const bool parentIsObject = parentTag == Tag::Object;
        if (info.tag == Tag::Object) {
            if (parentTag != Tag::Object && parentTag != Tag::Unknown)
                fail(node, fmt::format("<{}> cannot be nested in a property", name));
        } else if (isTransformOperation(info.tag)) {
            if (parentTag != Tag::Transform) fail(node, fmt::format("<{}> must be inside a <transform>", name));
        } else if (!parentIsObject) {
            fail(node, fmt::format("property <{}> must be inside an object element", name));
        }

        if (info.tag == Tag::Object) {
            // Objects nest by recursion: bound the depth so that a hostile file cannot overflow the stack.
            if (m_depth >= MaxObjectDepth)
                fail(node, fmt::format("objects nested more than {} deep", MaxObjectDepth));
            ++m_depth;
            std::unique_ptr<NoriObject> object = parseObject(node, info.classType);
            --m_depth;
            return object;
        }
        if (isTransformOperation(info.tag)) {
            parentTransform = parseTransformOperation(node, info.tag) * parentTransform;
            // Each operation may be fine and their product singular (two scales of 1e-25).
            if (!parentTransform.isInvertible())
                fail(node, "the transform becomes singular (or not finite) with this operation");
            return nullptr;
        }
        parseProperty(node, info.tag, parentProps);
        return nullptr;
    }

    void parseProperty(const pugi::xml_node &node, Tag tag, PropertyList &props) {
        const std::string name = attr(node, "name");
        const std::string loc = where(node);  // "file:line:col", kept for value errors
        if (tag == Tag::Transform) {
            checkAttributes(node, {"name"}, {"name"});
            Transform transform;
            PropertyList none;
            for (pugi::xml_node child : node.children()) parseElement(child, Tag::Transform, none, transform);
            props.setTransform(name, transform, loc);
            return;
        }
        checkAttributes(node, {"name", "value"}, {"name", "value"});
        for (pugi::xml_node child : node.children())
            if (child.type() == pugi::node_element)
                fail(child, fmt::format("property <{}> cannot contain <{}>", node.name(), child.name()));
        const std::string value = attr(node, "value");
        switch (tag) {
        case Tag::Boolean:
            if (value != "true" && value != "false")
                fail(node, fmt::format("boolean '{}' must be 'true' or 'false'", shown(value)));
            props.setBoolean(name, value == "true", loc);
            break;
        case Tag::Integer: props.setInteger(name, parseInteger(node, value), loc); break;
        case Tag::Float: props.setFloat(name, parseFloat(node, value, "float"), loc); break;
        case Tag::String: props.setString(name, value, loc); break;
        case Tag::Point: props.setPoint(name, parseVector(node, value, "point"), loc); break;
        case Tag::Vector: props.setVector(name, parseVector(node, value, "vector"), loc); break;
        case Tag::Color: props.setColor(name, parseVector(node, value, "color", true).array(), loc); break;
        default: fail(node, "unexpected property");
        }
    }

    std::unique_ptr<NoriObject> parseObject(const pugi::xml_node &node, NoriObject::EClassType classType) {
        const bool isScene = classType == NoriObject::EScene;
        if (isScene) checkAttributes(node, {"type"}, {});
        else checkAttributes(node, {"type"}, {"type"});
        std::string type = isScene ? "scene" : attr(node, "type");

        PropertyList props;
        props.setLocation(where(node));
        std::vector<std::unique_ptr<NoriObject>> children;
        Transform unusedTransform;
        bool hasAccel = false, hasSampler = false;
        for (pugi::xml_node child : node.children()) {
            std::unique_ptr<NoriObject> object = parseElement(child, Tag::Object, props, unusedTransform);
            if (!object) continue;
            hasAccel |= object->getClassType() == NoriObject::EAccel;
            hasSampler |= object->getClassType() == NoriObject::ESampler;
            children.push_back(std::move(object));
        }

        // Command-line overrides, and the defaults they need when the scene names no such object.
        if (classType == NoriObject::EAccel) {
            if (!m_overrides.accelType.empty()) type = m_overrides.accelType;
            props.overrideWith(m_overrides.accelProps);
        }
        if (classType == NoriObject::ESampler && m_overrides.sampleCount > 0) {
            PropertyList spp;
            spp.setInteger("sampleCount", m_overrides.sampleCount, "command line (--spp)");
            props.overrideWith(spp);
        }
        if (isScene && !hasAccel) children.push_back(defaultObject(NoriObject::EAccel, props.location()));
        if (isScene && !hasSampler) children.push_back(defaultObject(NoriObject::ESampler, props.location()));

        std::unique_ptr<NoriObject> object = NoriObjectFactory::createInstance(classType, type, props);
        object->setLocation(where(node));
        std::vector<std::string> unused = props.unusedProperties();
        if (!unused.empty())
            throw NoriException("{}: unused property '{}' in <{} type=\"{}\">", props.whereIs(unused.front()),
                                shown(unused.front()), node.name(), shown(type));
        for (auto &child : children) object->addChild(std::move(child));
        object->activate();
        return object;
    }

    /// An accel or sampler the scene does not declare, built from the command-line overrides.
    std::unique_ptr<NoriObject> defaultObject(NoriObject::EClassType classType, const std::string &location) {
        PropertyList props;
        props.setLocation(location);
        std::string type;
        if (classType == NoriObject::EAccel) {
            type = m_overrides.accelType;
            if (type.empty())
                type = NoriObjectFactory::isRegistered(classType, "octree") ? "octree" : "brute";
            props.overrideWith(m_overrides.accelProps);
        } else {
            type = "independent";
            if (m_overrides.sampleCount > 0)
                props.setInteger("sampleCount", m_overrides.sampleCount, "command line (--spp)");
        }
        std::unique_ptr<NoriObject> object = NoriObjectFactory::createInstance(classType, type, props);
        std::vector<std::string> unused = props.unusedProperties();
        if (!unused.empty())
            throw NoriException("{}: property '{}' does not apply to {} type '{}'", props.whereIs(unused.front()),
                                unused.front(), NoriObject::classTypeName(classType), type);
        object->activate();
        return object;
    }

    std::string m_path;
    std::string m_text;
    const SceneOverrides &m_overrides;
    std::vector<size_t> m_lineStarts;
    static constexpr int MaxObjectDepth = 64;
    int m_depth = 0;
};

/// A scene file larger than this is not a hand-written or generated scene but a mistake.
constexpr size_t MaxSceneBytes = size_t(64) << 20;

} // namespace

std::unique_ptr<NoriObject> loadFromXML(const std::string &path, const SceneOverrides &overrides) {
    std::string text = readInputFile(path, "scene file", MaxSceneBytes);
    // Files named in the scene are looked up next to it first (undone however parsing ends).
    std::string folder = std::filesystem::path(path).parent_path().string();
    fileResolver().prepend(folder.empty() ? "." : folder);
    struct PopFolder {
        ~PopFolder() { fileResolver().popFront(); }
    } popFolder;
    SceneParser parser(path, std::move(text), overrides);
    return parser.parse();
}

std::string rootElementName(const std::string &path) {
    const SceneOverrides none;
    SceneParser parser(path, readInputFile(path, "scene file", MaxSceneBytes), none);
    pugi::xml_document doc;
    return parser.documentElement(doc).name();
}

std::unique_ptr<Scene> loadScene(const std::string &path, const SceneOverrides &overrides) {
    std::unique_ptr<NoriObject> root = loadFromXML(path, overrides);
    if (root->getClassType() != NoriObject::EScene)
        throw NoriException("{}: the root element is <{}>, expected <scene> (or <test> for a test file)", root->location(),
                            NoriObject::classTypeName(root->getClassType()));
    return std::unique_ptr<Scene>(static_cast<Scene *>(root.release()));
}

} // namespace nori
