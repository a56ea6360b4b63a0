/// \file test_objloader.cpp
/// \brief Tests for the OBJ parser: statements, index forms, triangulation, attribute handling
// and error messages. File, gzip and real-mesh tests are in test_objloader_files.cpp.
#include <gtest/gtest.h>
#include <error_of.h>
#include <nori/objloader.h>
#include <cctype>
#include <unistd.h>

using namespace nori;
using namespace std::string_literals;

namespace {

using Tri = std::array<uint32_t, 3>;

MeshData parse(const std::string &text) { return parseObj(text, "test.obj"); }

std::string parseError(const std::string &text) {
    return errorOf([&] { parse(text); });
}

const char *Square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                     "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                     "vn 0 0 1\nvn 0 0 -1\n";

} // namespace

TEST(ObjLoader, PositionOnlyFacesIndexPositionsDirectly) {
    MeshData m = parse(std::string(Square) + "f 1 2 3\nf 3 4 1\n");
    ASSERT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.positions[2], Point3f(1, 1, 0));
    ASSERT_EQ(m.faces.size(), 2u);
    EXPECT_EQ(m.faces[0], (Tri{0, 1, 2}));
    EXPECT_EQ(m.faces[1], (Tri{2, 3, 0}));
    EXPECT_TRUE(m.uvs.empty());
    EXPECT_TRUE(m.normals.empty());
}

TEST(ObjLoader, UnreferencedVerticesAreKept) {
    MeshData m = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nf 1 2 3\n");
    EXPECT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.faces.size(), 1u);
}

TEST(ObjLoader, PositionAndTexCoordForm) {
    MeshData m = parse(std::string(Square) + "f 1/3 2/2 3/1\n");
    ASSERT_EQ(m.faces.size(), 1u);
    ASSERT_EQ(m.uvs.size(), m.positions.size());
    EXPECT_TRUE(m.normals.empty());
    const Tri &f = m.faces[0];
    EXPECT_EQ(m.positions[f[0]], Point3f(0, 0, 0));
    EXPECT_EQ(m.uvs[f[0]], Point2f(1, 1));
    EXPECT_EQ(m.positions[f[1]], Point3f(1, 0, 0));
    EXPECT_EQ(m.uvs[f[1]], Point2f(1, 0));
    EXPECT_EQ(m.positions[f[2]], Point3f(1, 1, 0));
    EXPECT_EQ(m.uvs[f[2]], Point2f(0, 0));
}

TEST(ObjLoader, PositionAndNormalForm) {
    MeshData m = parse(std::string(Square) + "f 1//2 2//2 3//1\n");
    ASSERT_EQ(m.normals.size(), m.positions.size());
    EXPECT_TRUE(m.uvs.empty());
    const Tri &f = m.faces[0];
    EXPECT_EQ(m.normals[f[0]], Normal3f(0, 0, -1));
    EXPECT_EQ(m.normals[f[2]], Normal3f(0, 0, 1));
    EXPECT_EQ(m.positions[f[2]], Point3f(1, 1, 0));
}

TEST(ObjLoader, FullForm) {
    MeshData m = parse(std::string(Square) + "f 4/1/1 3/2/2 2/4/1\n");
    ASSERT_EQ(m.positions.size(), 3u); // only the referenced triples become vertices
    ASSERT_EQ(m.uvs.size(), 3u);
    ASSERT_EQ(m.normals.size(), 3u);
    EXPECT_EQ(m.faces[0], (Tri{0, 1, 2})); // numbered in order of first use
    EXPECT_EQ(m.positions[0], Point3f(0, 1, 0));
    EXPECT_EQ(m.uvs[1], Point2f(1, 0));
    EXPECT_EQ(m.normals[1], Normal3f(0, 0, -1));
    EXPECT_EQ(m.positions[2], Point3f(1, 0, 0));
    EXPECT_EQ(m.uvs[2], Point2f(0, 1));
}

TEST(ObjLoader, NegativeIndicesAreRelativeToWhatIsDefinedSoFar) {
    MeshData m = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n"
                       "v 0 0 1\nv 1 0 1\nv 0 1 1\nf -1 -2 -3\nf 1 -1 2\n");
    ASSERT_EQ(m.faces.size(), 3u);
    EXPECT_EQ(m.faces[0], (Tri{0, 1, 2}));
    EXPECT_EQ(m.faces[1], (Tri{5, 4, 3}));
    EXPECT_EQ(m.faces[2], (Tri{0, 5, 1}));
}

TEST(ObjLoader, NegativeTexCoordAndNormalIndices) {
    MeshData m = parse(std::string(Square) + "f -4/-1/-1 -3/-2/-2 -2/-3/-1\n");
    const Tri &f = m.faces[0];
    EXPECT_EQ(m.positions[f[0]], Point3f(0, 0, 0));
    EXPECT_EQ(m.uvs[f[0]], Point2f(0, 1));
    EXPECT_EQ(m.normals[f[0]], Normal3f(0, 0, -1));
    EXPECT_EQ(m.uvs[f[2]], Point2f(1, 0));
    EXPECT_EQ(m.normals[f[1]], Normal3f(0, 0, 1));
}

TEST(ObjLoader, FacesMayReferenceVerticesDefinedLater) {
    MeshData m = parse("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
    ASSERT_EQ(m.faces.size(), 1u);
    EXPECT_EQ(m.faces[0], (Tri{0, 1, 2}));
}

TEST(ObjLoader, QuadIsFanTriangulated) {
    MeshData m = parse(std::string(Square) + "f 1 2 3 4\n");
    ASSERT_EQ(m.faces.size(), 2u);
    EXPECT_EQ(m.faces[0], (Tri{0, 1, 2}));
    EXPECT_EQ(m.faces[1], (Tri{0, 2, 3}));
}

TEST(ObjLoader, PentagonIsFanTriangulatedAroundItsFirstCorner) {
    MeshData m = parse("v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\nf 5 3 1 2 4\n");
    ASSERT_EQ(m.faces.size(), 3u);
    EXPECT_EQ(m.faces[0], (Tri{4, 2, 0}));
    EXPECT_EQ(m.faces[1], (Tri{4, 0, 1}));
    EXPECT_EQ(m.faces[2], (Tri{4, 1, 3}));
}

TEST(ObjLoader, QuadWithAttributesKeepsCornerAttributes) {
    MeshData m = parse(std::string(Square) + "f 1/1 2/2 3/3 4/4\n");
    ASSERT_EQ(m.faces.size(), 2u);
    ASSERT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.faces[0], (Tri{0, 1, 2}));
    EXPECT_EQ(m.faces[1], (Tri{0, 2, 3}));
    for (int i = 0; i < 4; ++i) EXPECT_EQ(m.uvs[i], m.positions[i].head<2>());
}

TEST(ObjLoader, SharedTriplesAreUnifiedAndDistinctOnesSplit) {
    // Faces 1-2 share (1,1) and (3,3); face 3 reuses position 1 with another uv, face 4
    // reuses (1,1) with a different normal: both need new vertices.
    MeshData m = parse(std::string(Square) + "f 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n"
                                             "f 1/3/1 2/2/1 4/4/1\nf 1/1/2 2/2/1 3/3/1\n");
    ASSERT_EQ(m.faces.size(), 4u);
    EXPECT_EQ(m.faces[0], (Tri{0, 1, 2}));
    EXPECT_EQ(m.faces[1], (Tri{0, 2, 3}));
    EXPECT_EQ(m.faces[2], (Tri{4, 1, 3}));
    EXPECT_EQ(m.faces[3], (Tri{5, 1, 2}));
    ASSERT_EQ(m.positions.size(), 6u);
    EXPECT_EQ(m.positions[4], Point3f(0, 0, 0));
    EXPECT_EQ(m.uvs[4], Point2f(1, 1));
    EXPECT_EQ(m.positions[5], Point3f(0, 0, 0));
    EXPECT_EQ(m.uvs[5], Point2f(0, 0));
    EXPECT_EQ(m.normals[5], Normal3f(0, 0, -1));
    EXPECT_EQ(m.normals[0], Normal3f(0, 0, 1));
}

TEST(ObjLoader, UnificationIgnoresDroppedAttribute) {
    // Normals are on every corner, uvs on only one face: uvs are dropped and two corners
    // that differed only in their uv index become one vertex.
    MeshData m = parse(std::string(Square) + "f 1/1/1 2/2/1 3/3/1\nf 1//1 3//1 4//1\nf 1/4/1 2/2/1 4/4/1\n");
    EXPECT_TRUE(m.uvs.empty());
    ASSERT_EQ(m.normals.size(), 4u);
    EXPECT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.faces[2], (Tri{0, 1, 3}));
}

TEST(ObjLoader, AttributeMissingOnSomeCornersIsDropped) {
    MeshData m = parse(std::string(Square) + "f 1/1/1 2/2/1 3/3/1\nf 1/1 3/3 4\n");
    EXPECT_TRUE(m.uvs.empty());
    EXPECT_TRUE(m.normals.empty());
    // Nothing left to unify: faces index the file's positions directly.
    EXPECT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.faces[1], (Tri{0, 2, 3}));
}

TEST(ObjLoader, AttributesWithoutFacesAreNotStored) {
    MeshData m = parse(Square);
    EXPECT_EQ(m.positions.size(), 4u);
    EXPECT_TRUE(m.faces.empty());
    EXPECT_TRUE(m.uvs.empty());
    EXPECT_TRUE(m.normals.empty());
}

TEST(ObjLoader, CrlfTabsAndTrailingWhitespace) {
    MeshData m = parse("v 0 0 0\r\nv\t1 0 0  \r\n  v 0 1 0\t\r\n\r\nf 1 2 3 \r\nf\t1/1\t2/1   3/1\r\nvt 0.5 0.25\r\n");
    ASSERT_EQ(m.faces.size(), 2u);
    EXPECT_EQ(m.positions[1], Point3f(1, 0, 0));
    EXPECT_EQ(m.faces[1], (Tri{0, 1, 2}));
}

TEST(ObjLoader, IgnoredStatements) {
    MeshData m = parse("# a comment\n\nmtllib scene.mtl\no thing\ng group one\ns 1\nusemtl red\n"
                       "v 0 0 0 1\nv 1 0 0 0.5\nv 0 1 0 0.2 0.3 0.4\n"
                       "vt 0 0 0\nvt 1 0 0\nvt 0 1 0\n"
                       "vp 0.5\ncstype bezier\nl 1 2\np 1\ns off\nf 1/1 2/2 3/3 # trailing\n");
    ASSERT_EQ(m.faces.size(), 1u);
    EXPECT_EQ(m.positions[2], Point3f(0, 1, 0));
    EXPECT_EQ(m.uvs[2], Point2f(0, 1));
}

TEST(ObjLoader, NumberForms) {
    MeshData m = parse("v +1 -.5 1e2\nv 1.5E-3 -0 2.\nv 1e-60 -1e-60 3\nf 1 2 3");
    EXPECT_EQ(m.positions[0], Point3f(1, -0.5f, 100));
    EXPECT_EQ(m.positions[1], Point3f(1.5e-3f, 0, 2));
    EXPECT_EQ(m.positions[2], Point3f(0, 0, 3)); // underflow reads as zero
    EXPECT_EQ(m.faces.size(), 1u);               // last line without '\n'
}

TEST(ObjLoader, TexCoordWithOnlyU) {
    MeshData m = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5\nf 1/1 2/1 3/1\n");
    EXPECT_EQ(m.uvs[0], Point2f(0.5f, 0));
}

TEST(ObjLoader, EmptyInputGivesEmptyMesh) {
    for (const char *text : {"", "\n\n", "# only a comment\n", "\xEF\xBB\xBF"}) {
        MeshData m = parse(text);
        EXPECT_TRUE(m.positions.empty());
        EXPECT_TRUE(m.faces.empty());
    }
}

TEST(ObjLoader, DegenerateTrianglesAreKept) {
    MeshData m = parse("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 1 2\nf 1 2 3\nf 3 3 3\n");
    ASSERT_EQ(m.faces.size(), 3u);
    EXPECT_EQ(m.faces[0], (Tri{0, 0, 1}));
    EXPECT_EQ(m.faces[2], (Tri{2, 2, 2}));
}

// ---- error messages -------------------------------------------------------------------

struct ErrorCase {
    std::string text;
    int line;
    const char *what; ///< a substring the message must contain
};

// Short printable name for test listings: letters and digits of the expected reason.
void PrintTo(const ErrorCase &c, std::ostream *os) {
    *os << "line" << c.line << "_";
    for (const char *p = c.what; *p; ++p) *os << (std::isalnum((unsigned char) *p) ? *p : '_');
}

class ObjLoaderError : public testing::TestWithParam<ErrorCase> {};

TEST_P(ObjLoaderError, ReportsFileLineAndReason) {
    const ErrorCase &c = GetParam();
    std::string msg = parseError(c.text);
    std::string prefix = fmt::format("test.obj:{}: ", c.line);
    EXPECT_EQ(msg.rfind(prefix, 0), 0u) << "message: " << msg << "\nexpected prefix: " << prefix;
    EXPECT_NE(msg.find(c.what), std::string::npos) << "message: " << msg << "\nexpected: " << c.what;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

#define TRI "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
const ErrorCase ErrorCases[] = {
    {"v 1 2 x\n"s, 1, "malformed number 'x'"},
    {"# c\nv 1.0abc 2 3\n"s, 2, "malformed number '1.0abc'"},
    {"v 1,5 2 3\n"s, 1, "malformed number"},
    {"v 1 2 3 w\n"s, 1, "malformed number 'w'"},
    {"vt 0.5 -\n"s, 1, "malformed number '-'"},
    {"vn 1 2 3\nvn 1 +-2 3\n"s, 2, "malformed number"},
    {"v 1 2\n"s, 1, "needs 3 coordinates, found 2"},
    {"\n\nv\n"s, 3, "needs 3 coordinates, found 0"},
    {"vn 0 1\n"s, 1, "needs 3 coordinates"},
    {"vt\n"s, 1, "needs 1 coordinate, found 0"},
    {"v nan 0 0\n"s, 1, "non-finite"},
    {"v 0 inf 0\n"s, 1, "non-finite"},
    {"vn 0 0 -infinity\n"s, 1, "non-finite"},
    {"vt NaN 0\n"s, 1, "non-finite"},
    {"v 1e39 0 0\n"s, 1, "out of range"},
    {TRI "f 1 2\n"s, 4, "face with 2 vertices"},
    {TRI "f\n"s, 4, "face with 0 vertices"},
    {TRI "f 1 # 2 3\n"s, 4, "face with 1 vertices"},
    {TRI "f 0 1 2\n"s, 4, "index 0"},
    {TRI "vt 0 0\nf 1/0 2/1 3/1\n"s, 5, "index 0"},
    {TRI "f 1 2 4\nv 0 0 1\nf 1 2 5\n"s, 6, "vertex index 5 out of range (the file has 4)"},
    {TRI "f 1 2 3\nf 3 2 99999999999\n"s, 5, "index out of range"},
    {TRI "f -4 -2 -1\n"s, 4, "relative vertex index -4 out of range"},
    {TRI "vt 0 0\nf 1/1 2/1 3/2\n"s, 5, "texture coordinate index 2 out of range (the file has 1)"},
    {TRI "vn 0 0 1\nf 1//1 2//1 3//-2\n"s, 5, "relative normal index -2"},
    {TRI "vn 0 0 1\nf 1//1 2//1 3//1\nf 1//1 2//1 3//3\n"s, 6, "normal index 3 out of range"},
    {TRI "f 1/ 2 3\n"s, 4, "malformed face vertex '1/'"},
    {TRI "vt 0 0\nf 1/1/ 2/1 3/1\n"s, 5, "malformed face vertex '1/1/'"},
    {TRI "f a b c\n"s, 4, "malformed face vertex 'a'"},
    {TRI "f 1//x 2 3\n"s, 4, "malformed face vertex '1//x'"},
    {TRI "f 1 2 3x\n"s, 4, "malformed face vertex '3x'"},
    {TRI "f 1 2 3.0\n"s, 4, "malformed face vertex '3.0'"},
    {"\x7f" "ELF\x02\x01\x01\x00\x00\x00\n\x03\x00"s, 1, "invalid statement '\\x7fELF\\x02"},
    {TRI "\x89PNG\r\n\x1a\n"s, 4, "invalid statement"},
    {TRI "g name\x01\x02\n"s, 4, "control character \\x01"},
    {TRI "# comment \x00 with a NUL\n"s, 4, "control character \\x00"},
    {TRI "v 1 2 \x00\n"s, 4, "malformed number '\\x00'"},
};
#undef TRI
INSTANTIATE_TEST_SUITE_P(Cases, ObjLoaderError, testing::ValuesIn(ErrorCases));

TEST(ObjLoaderError, BinaryGarbageAfterValidLines) {
    std::string text = "v 0 0 0\nv 1 0 0\n";
    for (int i = 0; i < 256; ++i) text += char((i * 37 + 11) & 0xff); // contains '\n' (10)
    std::string msg = parseError(text);
    EXPECT_EQ(msg.rfind("test.obj:3: ", 0), 0u) << msg;
}

TEST(ObjLoaderError, NameIsTheOneGiven) {
    std::string msg = errorOf([] { parseObj("v 1 2\n", "some/dir/mesh name.obj"); });
    EXPECT_EQ(msg, "some/dir/mesh name.obj:1: 'v' statement needs 3 coordinates, found 2");
}

// Old Mac files end lines with a lone CR; each is a line of its own, also in messages.
TEST(ObjLoader, CarriageReturnOnlyLineEndsAreLines) {
    MeshData m = parse("v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 3\r");
    EXPECT_EQ(m.positions.size(), 3u);
    EXPECT_EQ(m.faces.size(), 1u);
    EXPECT_EQ(parseError("v 0 0 0\rv 1 0 0\rv 0 1 x\r").rfind("test.obj:3: ", 0), 0u) << parseError("v 0 0 0\rv 1 0 0\rv 0 1 x\r");
    // CRLF stays one line end, not two.
    EXPECT_EQ(parseError("v 0 0 0\r\nv 1 0 0\r\nv 0 1 x\r\n").rfind("test.obj:3: ", 0), 0u);
}

// A '\' at the end of a line continues the statement on the next line (OBJ allows it); later
// lines keep their numbers in messages.
TEST(ObjLoader, BackslashContinuesTheLine) {
    MeshData m = parse("v 0 0 0\nv 1 \\\n0 0\nv 0 1 0\nf 1 \\\r\n 2 \\\n 3\n");
    ASSERT_EQ(m.positions.size(), 3u);
    EXPECT_EQ(m.positions[1], Point3f(1, 0, 0));
    ASSERT_EQ(m.faces.size(), 1u);
    EXPECT_EQ(m.faces[0], (Tri{0, 1, 2}));
    std::string error = parseError("v 0 0 \\\n0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n");
    EXPECT_EQ(error.rfind("test.obj:5: ", 0), 0u) << error;
}

// Prose (or points and lines only) has no triangles: the loader says so instead of an empty mesh.
TEST(ObjLoaderNoTriangles, FileWithoutFacesIsAnErrorNamingIt) {
    char name[] = "/tmp/nori-prose-XXXXXX";
    int fd = mkstemp(name);
    ASSERT_GE(fd, 0);
    const std::string prose = "This is a letter, not a mesh.\nIt has words and no faces.\n";
    ASSERT_EQ(write(fd, prose.data(), prose.size()), ssize_t(prose.size()));
    close(fd);
    std::string error = errorOf([&] { loadObjFile(name); });
    unlink(name);
    EXPECT_EQ(error, std::string(name) + ": no triangles (no 'f' statement with 3 or more vertices)");
}
