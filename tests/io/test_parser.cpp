/// \file test_parser.cpp
/// \brief Tests of the XML scene parser: properties, objects, overrides, locations in messages, and Nori's own scenes.
#include <gtest/gtest.h>
#include <nori/parser.h>
#include <nori/scene.h>
#include <filesystem>
#include <temp_dir.h>

using namespace nori;

namespace {

const char *kQuadObj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";

/// A valid scene around \p middle; line 1 is <scene>, \p middle starts on line 2.
std::string sceneWith(const std::string &middle) {
    return "<scene>\n" + middle +
           "<mesh type=\"obj\"><string name=\"filename\" value=\"quad.obj\"/></mesh>\n"
           "<camera type=\"perspective\"><integer name=\"width\" value=\"8\"/>"
           "<integer name=\"height\" value=\"8\"/></camera>\n"
           "</scene>\n";
}

/// Load \p text as a scene file and return the error message (empty if it loaded).
std::string loadError(const TempDir &dir, const std::string &text, std::string *pathOut = nullptr) {
    dir.write("quad.obj", kQuadObj);
    std::string path = dir.write("scene.xml", text);
    if (pathOut) *pathOut = path;
    try {
        loadScene(path);
    } catch (const NoriException &e) {
        return e.what();
    }
    return "";
}

/// The message must start with "PATH:LINE:" and contain \p fragment.
void expectError(const std::string &text, int line, const std::string &fragment) {
    TempDir dir;
    std::string path;
    std::string message = loadError(dir, text, &path);
    ASSERT_FALSE(message.empty()) << "scene loaded but should have failed:\n" << text;
    std::string prefix = path + ":" + std::to_string(line) + ":";
    EXPECT_EQ(message.rfind(prefix, 0), 0u) << "message: " << message << "\nexpected prefix: " << prefix;
    EXPECT_NE(message.find(fragment), std::string::npos) << "message: " << message << "\nexpected: " << fragment;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "message must be one line: " << message;
}

} // namespace

TEST(Parser, LoadsValidSceneWithDefaults) {
    TempDir dir;
    dir.write("quad.obj", kQuadObj);
    std::string path = dir.write("scene.xml", sceneWith("<integrator type=\"normals\"/>\n"));
    std::unique_ptr<Scene> scene = loadScene(path);
    ASSERT_EQ(scene->meshes().size(), 1u);
    EXPECT_EQ(scene->meshes()[0]->triangleCount(), 2u);
    EXPECT_EQ(scene->camera().outputSize(), Vector2i(8, 8));
    EXPECT_EQ(scene->sampler().sampleCount(), 1);
    EXPECT_EQ(scene->accel().triangleCount(), 2u);
}

TEST(Parser, TransformsComposeInDocumentOrder) {
    TempDir dir;
    dir.write("quad.obj", kQuadObj);
    // translate then scale: (1,0,0) -> (2,0,0) -> (4,0,0); the other order would give (3,0,0).
    std::string path = dir.write("scene.xml",
                                 "<scene><integrator type=\"normals\"/>\n"
                                 "<mesh type=\"obj\"><string name=\"filename\" value=\"quad.obj\"/>\n"
                                 "<transform name=\"toWorld\"><translate value=\"1,0,0\"/><scale value=\"2\"/></transform>\n"
                                 "</mesh><camera type=\"perspective\"/></scene>\n");
    std::unique_ptr<Scene> scene = loadScene(path);
    const Point3f &p = scene->meshes()[0]->positions()[1];
    EXPECT_FLOAT_EQ(p.x(), 4.0f);
    EXPECT_FLOAT_EQ(p.y(), 0.0f);
}

TEST(Parser, OverridesReplaceSampleCountAndAccel) {
    TempDir dir;
    dir.write("quad.obj", kQuadObj);
    std::string path = dir.write("scene.xml", sceneWith("<integrator type=\"normals\"/>\n<sampler type=\"independent\">"
                                                         "<integer name=\"sampleCount\" value=\"4\"/></sampler>\n"));
    SceneOverrides overrides;
    overrides.sampleCount = 7;
    overrides.accelType = "brute";
    std::unique_ptr<Scene> scene = loadScene(path, overrides);
    EXPECT_EQ(scene->sampler().sampleCount(), 7);
    EXPECT_NE(scene->accel().toString().find("Brute"), std::string::npos);
}

TEST(Parser, MalformedXml) { expectError("<scene>\n<integrator type=\"normals\">\n</scene>\n", 3, "XML error"); }
TEST(Parser, WrongEndTagNamesTheOpenElement) {
    expectError("<scene>\n<integrator type=\"normals\">\n</scene>\n", 3,
                "</scene> does not close <integrator> (opened on line 2)");
}
TEST(Parser, EndOfFileInsideAnElementPointsAtItsStartTag) {
    // Comments, CDATA, self-closing tags and a '>' inside a value must not confuse the search.
    expectError("<scene>\n<!-- <bsdf> -->\n<integrator type=\"normals\"></integrator>\n<mesh type=\"obj\">\n"
                "<string name=\"filename\" value=\"a>b.obj\"/>\n<![CDATA[ <x> ]]>\n",
                4, "<mesh> is never closed (the file ends first)");
}
TEST(Parser, UnknownElement) { expectError(sceneWith("<integrator type=\"normals\"/>\n<light/>\n"), 3, "unknown element"); }
TEST(Parser, UnknownType) {
    expectError(sceneWith("<integrator type=\"bdpt\"/>\n"), 2, "unknown integrator type 'bdpt'");
}
TEST(Parser, UnknownBsdfTypeInsideMesh) {
    expectError("<scene>\n<integrator type=\"normals\"/>\n<mesh type=\"obj\">\n<bsdf type=\"plastic\"/>\n"
                "<string name=\"filename\" value=\"quad.obj\"/></mesh><camera type=\"perspective\"/></scene>",
                4, "unknown bsdf type 'plastic'");
}
TEST(Parser, WrongPropertyType) {
    expectError("<scene>\n<integrator type=\"normals\"/>\n<camera type=\"perspective\">\n"
                "<integer name=\"fov\" value=\"30\"/>\n</camera>\n</scene>",
                4, "wrong type");
}
TEST(Parser, MissingRequiredProperty) { expectError(sceneWith("<integrator type=\"simple\"/>\n"), 2, "position"); }
TEST(Parser, UnusedProperty) {
    expectError(sceneWith("<integrator type=\"normals\">\n<float name=\"gain\" value=\"2\"/></integrator>\n"), 3,
                "unused property 'gain'");
}
TEST(Parser, DuplicateProperty) {
    expectError("<scene>\n<integrator type=\"normals\"/>\n<camera type=\"perspective\">\n"
                "<float name=\"fov\" value=\"30\"/>\n<float name=\"fov\" value=\"40\"/>\n</camera></scene>",
                5, "twice");
}
TEST(Parser, BadTransform) {
    expectError("<scene>\n<integrator type=\"normals\"/>\n<camera type=\"perspective\">\n<transform name=\"toWorld\">\n"
                "<scale value=\"0, 1, 1\"/>\n</transform></camera></scene>",
                5, "scale");
}
TEST(Parser, SingularMatrix) {
    expectError("<scene>\n<integrator type=\"normals\"/>\n<camera type=\"perspective\">\n<transform name=\"toWorld\">\n"
                "<matrix value=\"0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 1\"/>\n</transform></camera></scene>",
                5, "singular");
}
TEST(Parser, MalformedNumber) {
    expectError("<scene>\n<integrator type=\"normals\"/>\n<camera type=\"perspective\">\n"
                "<float name=\"fov\" value=\"3O\"/>\n</camera></scene>",
                4, "not a number");
}
TEST(Parser, NaNRejected) {
    expectError("<scene>\n<integrator type=\"normals\"/>\n<camera type=\"perspective\">\n"
                "<float name=\"fov\" value=\"nan\"/>\n</camera></scene>",
                4, "finite");
}
TEST(Parser, NonPositiveResolution) {
    expectError("<scene>\n<integrator type=\"normals\"/>\n<camera type=\"perspective\">\n"
                "<integer name=\"width\" value=\"0\"/>\n</camera></scene>",
                4, "width");
}
TEST(Parser, FovOutOfRange) {
    expectError("<scene>\n<integrator type=\"normals\"/>\n<camera type=\"perspective\">\n"
                "<float name=\"fov\" value=\"180\"/>\n</camera></scene>",
                4, "fov");
}
TEST(Parser, ZeroSampleCount) {
    expectError(sceneWith("<integrator type=\"normals\"/>\n<sampler type=\"independent\">\n"
                          "<integer name=\"sampleCount\" value=\"0\"/></sampler>\n"),
                4, "sampleCount");
}
TEST(Parser, MissingMeshFileNamesTheMeshFile) {
    TempDir dir;
    std::string path = dir.write("scene.xml", "<scene><integrator type=\"normals\"/><camera type=\"perspective\"/>\n"
                                              "<mesh type=\"obj\">\n<string name=\"filename\" value=\"nope.obj\"/>\n"
                                              "</mesh></scene>");
    try {
        loadScene(path);
        FAIL() << "should not load";
    } catch (const NoriException &e) {
        std::string message = e.what();
        EXPECT_NE(message.find(dir.file("nope.obj")), std::string::npos) << message;
        EXPECT_NE(message.find(path + ":3"), std::string::npos) << message;
    }
}
TEST(Parser, MissingSceneFile) {
    try {
        loadScene("/nonexistent/scene.xml");
        FAIL() << "should not load";
    } catch (const NoriException &e) {
        EXPECT_EQ(std::string(e.what()).rfind("/nonexistent/scene.xml: cannot open", 0), 0u) << e.what();
    }
}
TEST(Parser, SceneWithoutCamera) {
    expectError("<scene>\n<integrator type=\"normals\"/>\n</scene>", 1, "no <camera>");
}

TEST(Parser, NoriScenesLoadOrFailCleanly) {
    namespace fs = std::filesystem;
    fs::path root = fs::path(NORI_SHARED_DIR) / "nori-scenes";
    if (!fs::exists(root)) GTEST_SKIP() << "needs " << root;
    int loaded = 0, unknownType = 0, missingAjax = 0;
    for (const auto &entry : fs::recursive_directory_iterator(root)) {
        if (entry.path().extension() != ".xml") continue;
        SceneOverrides overrides;
        overrides.accelType = "brute";  // loading only: no need to build anything clever
        try {
            std::unique_ptr<NoriObject> root = loadFromXML(entry.path().string(), overrides);
            ++loaded;
        } catch (const NoriException &e) {
            std::string message = e.what();
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
            if (message.find("ajax.obj: cannot open") != std::string::npos) ++missingAjax;
            else if (message.find("unknown") != std::string::npos &&
                     message.rfind(entry.path().string() + ":", 0) == 0) ++unknownType;
            else ADD_FAILURE() << "unexpected error: " << message;
        }
    }
    EXPECT_EQ(loaded, 20);       // every scene and test file but those below
    EXPECT_EQ(missingAjax, 5);   // pa2, pa3 and pa5/ajax reference ajax.obj, which is not distributed
    EXPECT_EQ(unknownType, 0);   // every plugin Nori's files name exists
    std::printf("nori-scenes: %d loaded, %d unknown type, %d missing ajax.obj\n", loaded, unknownType, missingAjax);
}
