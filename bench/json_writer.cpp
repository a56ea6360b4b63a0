#include "json_writer.h"
#include "atomic_file.h"
#include <cmath>

namespace nori::bench {

namespace {

/// Minimal streaming JSON emitter: the caller opens and closes, commas are automatic.
class Emitter {
public:
    std::string out;

    void key(const std::string &k) {
        comma();
        out += quote(k) + ": ";
        m_needComma = false;
    }
    void value(double v) { raw(std::isfinite(v) ? fmt::format("{}", v) : std::string("null")); }
    void value(long long v) { raw(fmt::format("{}", v)); }
    void value(uint64_t v) { raw(fmt::format("{}", v)); }
    void value(int v) { raw(fmt::format("{}", v)); }
    void value(bool v) { raw(v ? "true" : "false"); }
    void value(const std::string &v) { raw(quote(v)); }
    void value(const char *v) { raw(quote(v)); }
    template <typename T> void field(const std::string &k, const T &v) { key(k); value(v); }
    void begin(char bracket) { comma(); out += bracket; m_needComma = false; }
    void end(char bracket) { out += bracket; m_needComma = true; }
    void newline(int indent) {
        if (m_needComma) out += ",";
        out += "\n" + std::string(size_t(indent), ' ');
        m_needComma = false;
    }

private:
    bool m_needComma = false;
    void comma() { if (m_needComma) out += ", "; }
    void raw(const std::string &s) { comma(); out += s; m_needComma = true; }
    static std::string quote(const std::string &s) {
        std::string q = "\"";
        for (unsigned char c : s) {
            if (c == '"' || c == '\\') { q += '\\'; q += char(c); }
            else if (c == '\n') q += "\\n";
            else if (c == '\t') q += "\\t";
            else if (c < 0x20) q += fmt::format("\\u{:04x}", int(c));
            else q += char(c);
        }
        return q + "\"";
    }
};

void emitSet(Emitter &j, const SetTiming &s, bool withRatio) {
    j.key(s.name);
    j.begin('{');
    j.field("rays", uint64_t(s.rays));
    j.field("ms", s.ms);
    j.field("mrays_s", s.mraysPerS);
    if (withRatio) {
        j.field("ratio_vs_embree", s.ratioVsEmbree);
        j.field("embree_ms", s.embreeMs);
    }
    if (s.hasAccuracy) {
        j.field("mismatches", s.accuracy.mismatches);
        j.field("hit_miss_mismatches", s.accuracy.hitMiss);
        j.field("max_rel_t_error", s.accuracy.maxRelTError);
    }
    j.key("samples_ms");
    j.begin('[');
    for (double v : s.samples) j.value(v);
    j.end(']');
    j.end('}');
}

void emitEmbree(Emitter &j, const EmbreeResult &e, bool robust) {
    j.begin('{');
    j.field("build_ms", e.buildMs);
    j.field("bytes", e.bytes);
    j.field("robust", robust);
    for (const SetTiming &s : e.sets) {
        j.newline(4);
        emitSet(j, s, robust);
    }
    j.end('}');
}

void emitRun(Emitter &j, const RunResult &r) {
    j.begin('{');
    j.field("accel", r.accel);
    j.field("default", r.hasConfig && r.config.isDefault);
    if (r.hasConfig) {
        j.field("maxDepth", r.config.maxDepth);
        j.field("leafSize", r.config.leafSize);
        j.field("overlap", r.config.overlap);
        j.field("traversal", r.config.traversal);
        j.field("intersector", r.config.intersector);
    }
    j.field("build_ms", r.buildMs);
    for (const AccelStat &s : r.stats) {
        if (s.name == "build_ms") continue;
        if (s.integral) j.field(s.name, (long long)std::llround(s.value));
        else j.field(s.name, s.value);
    }
    for (const SetTiming &s : r.sets) {
        j.newline(5);
        emitSet(j, s, true);
    }
    j.end('}');
}

void emitMesh(Emitter &j, const MeshResult &m) {
    j.begin('{');
    j.field("mesh", m.mesh);
    j.field("triangles", m.triangles);
    j.field("threads", m.threads);
    j.field("load_ms", m.loadMs);
    j.newline(1);
    j.key("rays");
    j.begin('{');
    j.field("camera", m.camera);
    j.field("width", m.width);
    j.field("height", m.height);
    j.field("spp", m.spp);
    j.field("repeats", m.repeats);
    j.field("generation_ms", m.rayGenerationMs);
    j.field("t_tolerance", Accuracy::Tolerance);
    j.field("reference", "embree_robust");
    j.end('}');
    j.newline(1);
    j.key("notes");
    j.begin('[');
    for (const std::string &n : m.notes) j.value(n);
    j.end(']');
    j.newline(1);
    j.key("embree");
    emitEmbree(j, m.embree, false);
    j.newline(1);
    j.key("embree_robust");
    emitEmbree(j, m.embreeRobust, true);
    j.newline(1);
    j.key("runs");
    j.begin('[');
    for (const RunResult &r : m.runs) {
        j.newline(2);
        emitRun(j, r);
    }
    j.end(']');
    j.end('}');
}

} // namespace

std::string JsonWriter::format(const std::vector<MeshResult> &results) {
    Emitter j;
    if (results.size() == 1) {
        emitMesh(j, results.front());
    } else {
        j.begin('[');
        for (const MeshResult &m : results) {
            j.newline(0);
            emitMesh(j, m);
        }
        j.end(']');
    }
    return j.out + "\n";
}

void JsonWriter::write(const std::string &path, const std::vector<MeshResult> &results) {
    AtomicFile::write(path, format(results));
}

} // namespace nori::bench
