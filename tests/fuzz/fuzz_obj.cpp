/// \file fuzz_obj.cpp
/// \brief libFuzzer entry point for the OBJ loader: any bytes must either parse or throw NoriException.
#include <nori/objloader.h>

#include <cstdio>
#include <string>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    std::string_view text(reinterpret_cast<const char *>(data), size);
    try {
        if (size >= 2 && data[0] == 0x1f && data[1] == 0x8b) {
            // gzip: the decompression path lives behind loadObjFile, which reads a file.
            static const std::string path = "/tmp/nori-fuzz-obj-" + std::to_string(getpid()) + ".obj.gz";
            FILE *f = std::fopen(path.c_str(), "wb");
            if (!f) return 0;
            std::fwrite(data, 1, size, f);
            std::fclose(f);
            nori::loadObjFile(path);
        } else {
            nori::MeshData mesh = nori::parseObj(text, "fuzz.obj");
            // Every face index the loader returns must be in range.
            for (const auto &face : mesh.faces)
                for (uint32_t i : face)
                    if (i >= mesh.positions.size()) __builtin_trap();
        }
    } catch (const nori::NoriException &) {
        // A clean error is the expected outcome for most inputs.
    }
    return 0;
}
