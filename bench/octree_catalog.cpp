/// \file octree_catalog.cpp
/// \brief The octree configurations to benchmark: the cross product of the option lists (implementation).
#include "octree_catalog.h"
#include <nori/object.h>
#include <regex>
#include <stdexcept>

namespace nori::bench {

std::string OctreeConfig::label() const {
    std::string extra;
    for (const auto &[name, value] : properties) extra += fmt::format(" {}={}", name, value);
    if (useDefaults && maxDepth == 0) return "octree (defaults)" + extra;
    return fmt::format("{}d={} l={} {} {} {}{}", buildRule.empty() ? "" : buildRule + " ", maxDepth, leafSize, overlap,
                       traversal, intersector, extra);
}

namespace {
/// Sets \p value as the type it reads as: true/false a boolean, an integer, a number, else a
/// string (the octree's getters check the type they expect).
void setTyped(PropertyList &props, const std::string &name, const std::string &value) {
    if (value == "true" || value == "false") return props.setBoolean(name, value == "true");
    static const std::regex integer(R"([+-]?[0-9]+)"), number(R"([+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?)");
    if (std::regex_match(value, integer)) {
        try {
            return props.setInteger(name, std::stoi(value));
        } catch (const std::out_of_range &) {
        }
    }
    if (std::regex_match(value, number)) return props.setFloat(name, std::stof(value));
    props.setString(name, value);
}
} // namespace

bool OctreeCatalog::available() { return NoriObjectFactory::isRegistered(NoriObject::EAccel, "octree"); }

std::unique_ptr<Accel> OctreeCatalog::create(const OctreeConfig &config) {
    PropertyList props;
    props.setLocation("<nori-bench>");
    if (!config.useDefaults) {
        if (!config.buildRule.empty()) props.setString("buildRule", config.buildRule);
        props.setInteger("maxDepth", config.maxDepth);
        props.setInteger("leafSize", config.leafSize);
        props.setString("overlap", config.overlap);
        props.setString("traversal", config.traversal);
        props.setString("intersector", config.intersector);
    }
    for (const auto &[name, value] : config.properties) setTyped(props, name, value);
    std::unique_ptr<NoriObject> object = NoriObjectFactory::createInstance(NoriObject::EAccel, "octree", props);
    const std::vector<std::string> unused = props.unusedProperties();
    if (!unused.empty()) throw std::invalid_argument(fmt::format("the octree has no property '{}'", unused.front()));
    object->activate();
    return std::unique_ptr<Accel>(static_cast<Accel *>(object.release()));
}

bool OctreeCatalog::accepts(const OctreeConfig &config, std::string &error) {
    try {
        create(config);
        return true;
    } catch (const std::exception &e) {
        error = e.what();
        return false;
    }
}

OctreeConfig OctreeCatalog::probeDefaults() {
    // The octree's defaults, read from its description ("maxDepth=20, traversal=..." or
    // similar); anything not found keeps a neutral value and matches no configuration.
    OctreeConfig d;
    d.useDefaults = true;
    OctreeConfig empty;
    empty.useDefaults = true;
    std::string text = create(empty)->toString();
    auto find = [&](const char *key) -> std::string {
        std::smatch m;
        std::regex re(std::string(key) + R"(\s*[=:]\s*\"?([A-Za-z0-9_.+-]+))", std::regex::icase);
        return std::regex_search(text, m, re) ? m[1].str() : std::string();
    };
    d.buildRule = find("buildRule");
    std::string depth = find("maxDepth"), leaf = find("leafSize");
    d.maxDepth = depth.empty() ? 0 : std::atoi(depth.c_str());
    d.leafSize = leaf.empty() ? 0 : std::atoi(leaf.c_str());
    d.overlap = find("overlap");
    d.traversal = find("traversal");
    d.intersector = find("intersector");
    return d;
}

OctreeCatalog::OctreeCatalog(const BenchOptions &options) {
    if (!available()) return;
    m_defaults = probeDefaults();

    // Traversals: as listed, or seed and sorted next to the octree's default (fast exact) one.
    std::vector<std::string> candidates = options.traversals;
    bool listed = !candidates.empty();
    if (!listed) {
        candidates = {"seed", "sorted"};
        if (!m_defaults.traversal.empty() && m_defaults.traversal != "seed" && m_defaults.traversal != "sorted")
            candidates.push_back(m_defaults.traversal);
    }
    // Probe with the octree's defaults, changing one setting at a time.
    OctreeConfig probe = m_defaults;
    probe.useDefaults = false;
    for (const std::string &t : candidates) {
        probe.traversal = t;
        std::string error;
        if (accepts(probe, error)) m_traversals.push_back(t);
        else if (listed) throw std::invalid_argument(fmt::format("--traversals: the octree rejects '{}': {}", t, error));
    }
    // --octree-set: checked once on the defaults, then given to every run.
    auto withProperties = [&] {
        if (options.octreeProperties.empty()) return;
        OctreeConfig d = m_defaults;
        d.properties = options.octreeProperties;
        std::string error;
        if (!accepts(d, error)) throw std::invalid_argument("--octree-set: " + error);
        for (OctreeConfig &c : m_configs) c.properties = options.octreeProperties;
    };
    if (options.defaultOnly) {  // the lists do not matter
        m_configs.push_back(m_defaults);
        m_configs.back().isDefault = true;
        withProperties();
        return;
    }
    // Every other list value once, so that a bad value fails before anything is measured.
    auto check = [&](const char *option, OctreeConfig c, const std::string &what) {
        c.traversal = m_traversals.empty() ? std::string("sorted") : m_traversals.front();
        std::string error;
        if (accepts(c, error)) return true;
        if (options.wasGiven(option))
            throw std::invalid_argument(fmt::format("{}: the octree rejects {}: {}", option, what, error));
        m_skipped.push_back(fmt::format("{} {} (default list) skipped: {}", option, what, error));
        return false;
    };
    std::vector<int> depths, leaves;
    std::vector<std::string> rules, overlaps, intersectors;
    for (const std::string &b : options.buildRules.empty() ? std::vector<std::string>{m_defaults.buildRule}
                                                            : options.buildRules) {
        OctreeConfig c = probe;
        c.buildRule = b;
        if (check("--build-rules", c, fmt::format("buildRule {}", b))) rules.push_back(b);
    }
    for (int d : options.depths) {
        OctreeConfig c = probe;
        c.maxDepth = d;
        if (check("--depths", c, fmt::format("maxDepth {}", d))) depths.push_back(d);
    }
    for (int l : options.leafSizes) {
        OctreeConfig c = probe;
        c.leafSize = l;
        if (check("--leaf-sizes", c, fmt::format("leafSize {}", l))) leaves.push_back(l);
    }
    for (const std::string &o : options.overlaps) {
        OctreeConfig c = probe;
        c.overlap = o;
        if (check("--overlaps", c, fmt::format("overlap {}", o))) overlaps.push_back(o);
    }
    for (const std::string &i : options.intersectors) {
        OctreeConfig c = probe;
        c.intersector = i;
        if (check("--intersectors", c, fmt::format("intersector {}", i))) intersectors.push_back(i);
    }

    // Order: build rule, overlap, leaf size, depth, traversal, intersector (the Markdown table
    // reads like the seed's: one column per depth).
    bool haveDefault = false;
    for (const std::string &b : rules)
    for (const std::string &o : overlaps)
        for (int leaf : leaves)
            for (int depth : depths)
                for (const std::string &t : m_traversals)
                    for (const std::string &i : intersectors) {
                        OctreeConfig c;
                        c.buildRule = b;
                        c.maxDepth = depth;
                        c.leafSize = leaf;
                        c.overlap = o;
                        c.traversal = t;
                        c.intersector = i;
                        c.isDefault = c.sameSettings(m_defaults);
                        haveDefault = haveDefault || c.isDefault;
                        m_configs.push_back(c);
                    }
    // The octree's defaults are what the renderer uses: always measure them.
    if (!haveDefault && !m_traversals.empty()) {
        OctreeConfig d = m_defaults;
        d.isDefault = true;
        m_configs.push_back(d);
    }
    withProperties();
}

} // namespace nori::bench
