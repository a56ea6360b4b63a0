/// \file fuzz_scene.cpp
/// \brief libFuzzer entry point for the XML scene parser: the bytes are written to a scene file in a
/// private folder (beside a small valid mesh, so that mesh loading is reachable) and loaded.
#include <nori/parser.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <unistd.h>

namespace {

std::string makeFolder() {
    char pattern[] = "/tmp/nori-fuzz-scene-XXXXXX";
    if (!mkdtemp(pattern)) std::abort();
    std::string folder = pattern;
    FILE *f = std::fopen((folder + "/m.obj").c_str(), "w");
    if (!f) std::abort();
    std::fputs("v 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\nf 1 2 3\nf 2 4 3\n", f);
    std::fclose(f);
    return folder;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    static const std::string folder = makeFolder();
    static const std::string path = folder + "/scene.xml";
    std::string text(reinterpret_cast<const char *>(data), size);
    // Keep the fuzzer away from device files and the like: reading /dev/zero as a mesh
    // would only measure how long it takes to run out of memory.
    for (const char *special : {"/dev", "/proc", "/sys", "/run"})
        if (text.find(special) != std::string::npos) return 0;
    FILE *f = std::fopen(path.c_str(), "wb");
    if (!f) return 0;
    std::fwrite(data, 1, size, f);
    std::fclose(f);
    try {
        nori::loadFromXML(path);
    } catch (const nori::NoriException &) {
        // A clean, located error is the expected outcome for most inputs.
    }
    return 0;
}
