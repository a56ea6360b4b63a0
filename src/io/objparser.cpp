/// \file objparser.cpp
/// \brief OBJ text -> MeshData: a single pass over the in-memory text, then (only when the
/// file references vt/vn) unification of (v, vt, vn) index triples into output vertices.
#include <nori/objloader.h>
#include <charconv>
#include <cmath>
#include <cstring>

namespace nori {
namespace {

constexpr uint32_t NoIndex = 0xffffffffu;
enum Attr { AttrV = 0, AttrT = 1, AttrN = 2 };
const char *const AttrName[3] = {"vertex", "texture coordinate", "normal"};

inline bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
inline bool isKeywordChar(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}
/// Bytes that never occur in an OBJ text line; they mean binary data.
inline bool isControl(char c) {
    unsigned char u = (unsigned char) c;
    return (u < 0x20 && !isSpace(c)) || u == 0x7f;
}
inline const char *skipSpace(const char *p, const char *eol) {
    while (p != eol && isSpace(*p)) ++p;
    return p;
}
inline const char *tokenEnd(const char *p, const char *eol) {
    while (p != eol && !isSpace(*p)) ++p;
    return p;
}

/// A token quoted for an error message: bounded length, non-printable bytes escaped,
/// so that the message always stays on one line.
std::string quote(const char *begin, const char *end) {
    std::string out = "'";
    const size_t maxLen = 40;
    for (const char *p = begin; p != end; ++p) {
        if (size_t(p - begin) == maxLen) {
            out += "...";
            break;
        }
        unsigned char u = (unsigned char) *p;
        if (u < 0x20 || u >= 0x7f) out += fmt::format("\\x{:02x}", u);
        else out += *p;
    }
    return out + "'";
}

/// One pass over the text. \p limits bounds positive indices: on the first pass they are
/// unbounded (vertices may follow the faces that use them); the error path re-runs the
/// parser with the final counts to find the first offending line.
class ObjParser {
public:
    ObjParser(std::string_view text, const std::string &name, const uint32_t limits[3])
        : m_text(text), m_name(name) {
        std::copy(limits, limits + 3, m_limit);
        // Cheap guesses (bytes per statement in typical files) to avoid most regrowth.
        positions.reserve(text.size() / 80);
        facesV.reserve(text.size() / 60);
    }

    void run() {
        const char *p = m_text.data(), *end = p + m_text.size();
        if (m_text.size() >= 3 && std::memcmp(p, "\xEF\xBB\xBF", 3) == 0) p += 3; // UTF-8 BOM
        while (p != end) {
            ++m_line;
            const char *eol = static_cast<const char *>(std::memchr(p, '\n', size_t(end - p)));
            if (!eol) eol = end;
            parseLine(p, eol);
            p = eol == end ? end : eol + 1;
        }
    }

    std::vector<Point3f> positions;
    std::vector<Point2f> uvs;
    std::vector<Normal3f> normals;
    /// Triangulated corners: position indices always; vt / vn only while every corner had one.
    std::vector<std::array<uint32_t, 3>> facesV, facesT, facesN;
    bool allT = true, allN = true; ///< every face corner so far has a vt / vn index
    uint32_t maxIndex[3] = {0, 0, 0};  ///< largest positive (1-based) index per attribute

    uint32_t count(int attr) const {
        size_t n = attr == AttrV ? positions.size() : attr == AttrT ? uvs.size() : normals.size();
        return uint32_t(std::min<size_t>(n, NoIndex));
    }

private:
    [[noreturn, gnu::cold, gnu::noinline]] void fail(const std::string &what) const {
        throw NoriException("{}:{}: {}", m_name, m_line, what);
    }

    void parseLine(const char *p, const char *eol) {
        p = skipSpace(p, eol);
        if (p == eol) return;
        auto sepAt = [eol](const char *q) { return q == eol || isSpace(*q); };
        if (p[0] == 'v') {
            if (sepAt(p + 1)) return parseVertex(p + 1, eol);
            if (p[1] == 't' && sepAt(p + 2)) return parseTexCoord(p + 2, eol);
            if (p[1] == 'n' && sepAt(p + 2)) return parseNormal(p + 2, eol);
        } else if (p[0] == 'f' && sepAt(p + 1)) {
            return parseFace(p + 1, eol);
        }
        parseIgnored(p, eol);
    }

    /// Comments and statements we do not use: only check that the line is text.
    void parseIgnored(const char *p, const char *eol) {
        const char *q = p;
        if (*q != '#') {
            while (q != eol && isKeywordChar(*q)) ++q;
            if (q == p || (q != eol && !isSpace(*q)))
                fail(fmt::format("invalid statement {} (not OBJ text)", quote(p, tokenEnd(p, eol))));
        }
        for (; q != eol; ++q)
            if (isControl(*q)) fail(fmt::format("control character \\x{:02x} in line (binary data?)", (int) *q));
    }

    /// A finite float followed by whitespace or the end of the line.
    float readFloat(const char *&p, const char *eol, const char *stmt) {
        const char *start = p;
        if (*p == '+' && p + 1 != eol && p[1] != '-') ++p; // from_chars rejects an explicit '+'
        float value = 0.0f;
        auto [ptr, ec] = std::from_chars(p, eol, value);
        if (ec == std::errc::invalid_argument || (ptr != eol && !isSpace(*ptr)))
            fail(fmt::format("malformed number {} in '{}' statement", quote(start, tokenEnd(start, eol)), stmt));
        if (ec == std::errc::result_out_of_range) value = underflowOrFail(p, ptr, stmt);
        if (!std::isfinite(value))
            fail(fmt::format("non-finite number {} in '{}' statement", quote(start, ptr), stmt));
        p = ptr;
        return value;
    }

    /// from_chars reports both overflow and underflow as out of range: underflow reads as 0.
    [[gnu::cold]] float underflowOrFail(const char *begin, const char *end, const char *stmt) {
        double d = 0.0;
        auto [ptr, ec] = std::from_chars(begin, end, d);
        if (ec == std::errc() && std::fabs(d) < 1.0) return float(d);
        std::string_view tok(begin, size_t(end - begin));
        size_t e = tok.find_first_of("eE");
        if (ec != std::errc() && e != std::string_view::npos && e + 1 < tok.size() && tok[e + 1] == '-')
            return *begin == '-' ? -0.0f : 0.0f; // below even the double range
        fail(fmt::format("number {} out of range in '{}' statement", quote(begin, end), stmt));
    }

    /// \p n required numbers; extra numbers (w, vertex colours) are checked and ignored.
    template <int N> void readNumbers(const char *p, const char *eol, const char *stmt, int required, float *out) {
        for (int i = 0; i < N; ++i) {
            p = skipSpace(p, eol);
            if (p == eol || *p == '#') {
                if (i < required)
                    fail(fmt::format("'{}' statement needs {} coordinate{}, found {}", stmt, required,
                                     required == 1 ? "" : "s", i));
                out[i] = 0.0f;
                continue;
            }
            out[i] = readFloat(p, eol, stmt);
        }
        while ((p = skipSpace(p, eol)) != eol && *p != '#') readFloat(p, eol, stmt);
    }

    void parseVertex(const char *p, const char *eol) {
        float x[3];
        readNumbers<3>(p, eol, "v", 3, x);
        positions.emplace_back(x[0], x[1], x[2]);
    }
    void parseTexCoord(const char *p, const char *eol) {
        float x[2];
        readNumbers<2>(p, eol, "vt", 1, x); // the OBJ spec makes v optional (default 0)
        uvs.emplace_back(x[0], x[1]);
    }
    void parseNormal(const char *p, const char *eol) {
        float x[3];
        readNumbers<3>(p, eol, "vn", 3, x);
        normals.emplace_back(x[0], x[1], x[2]);
    }

    [[noreturn, gnu::cold]] void failCorner(const char *tok, const char *eol, const char *why) const {
        fail(fmt::format("{} face vertex {}", why, quote(tok, tokenEnd(tok, eol))));
    }

    /// One index of a face corner, resolved to 0-based. Negative indices count back from the
    /// last element defined so far.
    uint32_t readIndex(const char *&p, const char *eol, int attr, const char *tok) {
        bool negative = p != eol && *p == '-';
        if (negative) ++p;
        const char *digits = p;
        uint64_t v = 0;
        while (p != eol && unsigned(*p - '0') < 10u) {
            v = v * 10 + unsigned(*p - '0');
            if (v > NoIndex) failCorner(tok, eol, "index out of range in");
            ++p;
        }
        if (p == digits) failCorner(tok, eol, "malformed");
        if (v == 0) failCorner(tok, eol, "index 0 (OBJ indices start at 1) in");
        if (negative) {
            uint32_t n = count(attr);
            if (v > n)
                fail(fmt::format("relative {} index -{} out of range (only {} defined so far) in face vertex {}",
                                 AttrName[attr], v, n, quote(tok, tokenEnd(tok, eol))));
            return uint32_t(n - v);
        }
        if (v > maxIndex[attr]) {
            maxIndex[attr] = uint32_t(v);
            if (v > m_limit[attr])
                fail(fmt::format("{} index {} out of range (the file has {}) in face vertex {}", AttrName[attr],
                                 v, m_limit[attr], quote(tok, tokenEnd(tok, eol))));
        }
        return uint32_t(v - 1);
    }

    void parseFace(const char *p, const char *eol) {
        uint32_t first[3], prev[3];
        int n = 0;
        while ((p = skipSpace(p, eol)) != eol && *p != '#') {
            const char *tok = p;
            uint32_t c[3] = {NoIndex, NoIndex, NoIndex};
            c[AttrV] = readIndex(p, eol, AttrV, tok);
            if (p != eol && *p == '/') {
                ++p;
                if (p != eol && *p == '/') {
                    ++p;
                    c[AttrN] = readIndex(p, eol, AttrN, tok); // i//k
                } else {
                    c[AttrT] = readIndex(p, eol, AttrT, tok); // i/j
                    if (p != eol && *p == '/') {
                        ++p;
                        c[AttrN] = readIndex(p, eol, AttrN, tok); // i/j/k
                    }
                }
            }
            if (p != eol && !isSpace(*p)) failCorner(tok, eol, "malformed");
            // Once one corner lacks an attribute, the attribute is dropped for the whole mesh.
            if (c[AttrT] == NoIndex && allT) allT = false, facesT = {};
            if (c[AttrN] == NoIndex && allN) allN = false, facesN = {};
            if (n == 0) {
                std::copy(c, c + 3, first);
            } else if (n >= 2) { // fan triangulation around the first corner
                facesV.push_back({first[AttrV], prev[AttrV], c[AttrV]});
                if (allT) facesT.push_back({first[AttrT], prev[AttrT], c[AttrT]});
                if (allN) facesN.push_back({first[AttrN], prev[AttrN], c[AttrN]});
            }
            std::copy(c, c + 3, prev);
            ++n;
        }
        if (n < 3) fail(fmt::format("face with {} vertices (needs at least 3)", n));
    }

    std::string_view m_text;
    const std::string &m_name;
    uint32_t m_limit[3];
    size_t m_line = 0;
};

/// Unify distinct (v, vt, vn) triples into output vertices, numbered in order of first use
/// (deterministic). The table is a hash map keyed directly by the position index: one
/// chain per position, holding the output vertices that share it (typically 1-4 entries).
MeshData unify(ObjParser &P, bool useT, bool useN) {
    const size_t nPos = P.positions.size(), nTri = P.facesV.size();
    std::vector<uint32_t> head(nPos, NoIndex), next, srcV, srcT, srcN;
    for (auto *v : {&next, &srcV, &srcT, &srcN}) v->reserve(nPos + nPos / 4);
    MeshData data;
    data.faces.resize(nTri);
    for (size_t f = 0; f < nTri; ++f) {
        for (int k = 0; k < 3; ++k) {
            uint32_t v = P.facesV[f][k], t = useT ? P.facesT[f][k] : 0, n = useN ? P.facesN[f][k] : 0;
            uint32_t o = head[v];
            while (o != NoIndex && (srcT[o] != t || srcN[o] != n)) o = next[o];
            if (o == NoIndex) {
                o = uint32_t(srcV.size());
                srcV.push_back(v), srcT.push_back(t), srcN.push_back(n);
                next.push_back(head[v]);
                head[v] = o;
            }
            data.faces[f][k] = o;
        }
    }
    const size_t nOut = srcV.size();
    data.positions.resize(nOut);
    for (size_t o = 0; o < nOut; ++o) data.positions[o] = P.positions[srcV[o]];
    if (useT) {
        data.uvs.resize(nOut);
        for (size_t o = 0; o < nOut; ++o) data.uvs[o] = P.uvs[srcT[o]];
    }
    if (useN) {
        data.normals.resize(nOut);
        for (size_t o = 0; o < nOut; ++o) data.normals[o] = P.normals[srcN[o]];
    }
    return data;
}

/// Does \p text have a line ending in '\\' (a continuation) or a CR not followed by LF?
bool needsLineNormalizing(std::string_view text) {
    for (size_t i = text.find('\r'); i != std::string_view::npos; i = text.find('\r', i + 1))
        if (i + 1 == text.size() || text[i + 1] != '\n') return true;
    for (size_t i = text.find('\\'); i != std::string_view::npos; i = text.find('\\', i + 1))
        if (i + 1 == text.size() || text[i + 1] == '\n' || text[i + 1] == '\r') return true;
    return false;
}

/// LF line ends only: a lone CR (old Mac files) ends a line, and a '\\' at the end of a line
/// joins the next one. The newline a continuation removes is put back after the joined
/// statement, so every later line keeps its number in error messages.
std::string normalizeLines(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    size_t owed = 0;  // newlines removed by continuations of the current statement
    auto lineEndAt = [&](size_t i) { return i < text.size() && (text[i] == '\n' || text[i] == '\r'); };
    auto skipLineEnd = [&](size_t i) { return text[i] == '\r' && i + 1 < text.size() && text[i + 1] == '\n' ? i + 1 : i; };
    for (size_t i = 0; i < text.size(); ++i) {
        char c = text[i];
        if (c == '\\' && (i + 1 == text.size() || lineEndAt(i + 1))) {
            out += ' ';
            if (i + 1 < text.size()) {
                i = skipLineEnd(i + 1);
                ++owed;
            }
            continue;
        }
        if (c == '\r') {
            i = skipLineEnd(i);
            c = '\n';
        }
        out += c;
        if (c == '\n') {
            out.append(owed, '\n');
            owed = 0;
        }
    }
    return out;
}

/// parseObj() for text with LF line ends only.
MeshData parseLines(std::string_view text, const std::string &name) {
    const uint32_t unbounded[3] = {NoIndex, NoIndex, NoIndex};
    ObjParser P(text, name, unbounded);
    P.run();

    // Positive indices may point forward, so their range is only known now.
    uint32_t counts[3] = {P.count(AttrV), P.count(AttrT), P.count(AttrN)};
    for (int a = 0; a < 3; ++a) {
        if (P.maxIndex[a] > counts[a]) {
            ObjParser locate(text, name, counts);
            locate.run(); // throws at the first face with an out-of-range index
            throw NoriException("{}: {} index {} out of range (the file has {})", name, AttrName[a],
                                P.maxIndex[a], counts[a]);
        }
    }

    const bool hasFaces = !P.facesV.empty();
    const bool useT = hasFaces && P.allT, useN = hasFaces && P.allN;
    if (!useT && !useN) { // fast path: faces index the positions directly
        MeshData data;
        data.positions = std::move(P.positions);
        data.faces = std::move(P.facesV);
        return data;
    }
    return unify(P, useT, useN);
}

} // namespace

MeshData parseObj(std::string_view text, const std::string &name) {
    if (!needsLineNormalizing(text)) return parseLines(text, name);
    return parseLines(normalizeLines(text), name);
}

} // namespace nori
