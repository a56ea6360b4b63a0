/// \file objload.cpp
/// \brief nori-objload: time our OBJ loader against tinyobjloader and plain zlib decompression.
//
//   nori-objload FILE [REPEATS]
//
// Every figure is the median of REPEATS runs (default 7). tinyobjloader parses the same
// in-memory text (already decompressed) through a std::istringstream built outside the
// timed region, so its figure is parse time only; "zlib inflate" is the decompression
// alone (what `gzip -dc` does). Exits with status 1 when the triangle counts differ.
#define TINYOBJLOADER_IMPLEMENTATION // header-only build, same compiler flags as ours
#include <tiny_obj_loader.h>

#include <app/cli_app.h>
#include <nori/objloader.h>
#include <benchmark/benchmark.h>
#include <zlib.h>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>

using namespace nori;

namespace {

std::string readAll(const std::string &path) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) throw NoriException("{}: cannot open", path);
    std::string data(size_t(in.tellg()), '\0');
    in.seekg(0);
    in.read(data.data(), std::streamsize(data.size()));
    return data;
}

bool isGzip(const std::string &d) { return d.size() >= 2 && (unsigned char) d[0] == 0x1f && (unsigned char) d[1] == 0x8b; }

/// Plain zlib inflate of a whole .gz buffer (single or multiple members), big output chunks.
std::string inflateAll(const std::string &in) {
    size_t hint = in.size() * 4;
    if (in.size() >= 18) {
        auto *t = reinterpret_cast<const unsigned char *>(in.data() + in.size() - 4);
        hint = size_t(t[0]) | size_t(t[1]) << 8 | size_t(t[2]) << 16 | size_t(t[3]) << 24;
    }
    std::string out(hint + 1, '\0');
    z_stream zs{};
    inflateInit2(&zs, 15 + 16);
    zs.next_in = reinterpret_cast<Bytef *>(const_cast<char *>(in.data()));
    zs.avail_in = uInt(in.size());
    size_t produced = 0;
    for (;;) {
        if (produced == out.size()) out.resize(out.size() * 2);
        zs.next_out = reinterpret_cast<Bytef *>(&out[produced]);
        zs.avail_out = uInt(out.size() - produced);
        uInt before = zs.avail_out;
        int ret = inflate(&zs, Z_NO_FLUSH);
        produced += before - zs.avail_out;
        if (ret == Z_STREAM_END && zs.avail_in >= 2 && zs.next_in[0] == 0x1f) {
            inflateReset(&zs);
            continue;
        }
        if (ret == Z_STREAM_END) break;
        if (ret != Z_OK && !(ret == Z_BUF_ERROR && produced == out.size())) {
            inflateEnd(&zs);
            throw NoriException("corrupt gzip data");
        }
    }
    inflateEnd(&zs);
    out.resize(produced);
    return out;
}

/// Median wall time in milliseconds of \p repeats calls; \p setup runs untimed before each.
double medianMs(int repeats, const std::function<void()> &run, const std::function<void()> &setup = {}) {
    std::vector<double> ms;
    for (int i = 0; i < repeats; ++i) {
        if (setup) setup();
        auto t0 = std::chrono::steady_clock::now();
        run();
        auto t1 = std::chrono::steady_clock::now();
        ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    }
    std::sort(ms.begin(), ms.end());
    return ms[ms.size() / 2];
}

struct TinyResult {
    size_t triangles = 0, positions = 0, texcoords = 0, normals = 0;
};

TinyResult tinyParse(std::istream &in) {
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, nullptr, true, false))
        throw NoriException("tinyobjloader failed: {}", err);
    TinyResult r;
    for (const auto &s : shapes) r.triangles += s.mesh.num_face_vertices.size();
    r.positions = attrib.vertices.size() / 3;
    r.texcoords = attrib.texcoords.size() / 2;
    r.normals = attrib.normals.size() / 3;
    return r;
}

} // namespace

int main(int argc, char **argv) {
    CliApp cli("nori-objload", "Times nori's OBJ loader against tinyobjloader and plain zlib decompression.");
    std::string path;
    int repeats = 7;
    cli.app().add_option("file", path, "the mesh (.obj or .obj.gz)")->required()->option_text("FILE");
    cli.app().add_option("repeats", repeats, "runs per figure; the median is reported (default 7)")
        ->check(integerIn(1, 1000))
        ->option_text("REPEATS");
    if (std::optional<int> status = cli.parse(argc, argv)) return *status;
    try {
        const std::string raw = readAll(path);
        const bool gz = isGzip(raw);
        const std::string text = gz ? inflateAll(raw) : raw;
        std::printf("%s: %s, %zu bytes on disk, %zu bytes of text; median of %d runs\n", path.c_str(),
                    gz ? "gzip" : "plain", raw.size(), text.size(), repeats);

        double tRead = medianMs(repeats, [&] { benchmark::DoNotOptimize(readAll(path)); });
        double tInflate = gz ? medianMs(repeats, [&] { benchmark::DoNotOptimize(inflateAll(raw)); }) : 0.0;

        MeshData ours;
        double tOursFile = medianMs(repeats, [&] { ours = loadObjFile(path); });
        double tOursText = medianMs(repeats, [&] { benchmark::DoNotOptimize(parseObj(text, path)); });

        TinyResult tiny;
        std::istringstream stream;
        double tTiny = medianMs(
            repeats, [&] { tiny = tinyParse(stream); }, [&] { stream = std::istringstream(text); });

        std::printf("  file read                           : %8.1f ms\n", tRead);
        if (gz) std::printf("  zlib inflate only (gzip -dc equiv.) : %8.1f ms\n", tInflate);
        std::printf("  ours: loadObjFile (read+inflate+parse): %6.1f ms\n", tOursFile);
        std::printf("  ours: parseObj on in-memory text    : %8.1f ms\n", tOursText);
        std::printf("  tinyobj: LoadObj on in-memory text  : %8.1f ms   (+ inflate = %.1f ms)\n", tTiny,
                    tTiny + tInflate);
        if (gz) std::printf("  ours / zlib-only                    : %8.2f x\n", tOursFile / tInflate);
        std::printf("  tinyobj parse / ours parse          : %8.2f x\n", tTiny / tOursText);
        std::printf("  ours   : %zu triangles, %zu vertices, uvs %s, normals %s\n", ours.faces.size(),
                    ours.positions.size(), ours.uvs.empty() ? "no" : "yes", ours.normals.empty() ? "no" : "yes");
        std::printf("  tinyobj: %zu triangles, %zu v, %zu vt, %zu vn\n", tiny.triangles, tiny.positions,
                    tiny.texcoords, tiny.normals);
        if (tiny.triangles != ours.faces.size()) {
            std::printf("  MISMATCH: triangle counts differ\n");
            return 1;
        }
        std::printf("  triangle counts match\n");
    } catch (const std::exception &e) {
        std::fprintf(stderr, "nori-objload: %s\n", oneLine(e.what()).c_str());
        return 1;
    }
    return 0;
}
