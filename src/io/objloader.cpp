/// \file objloader.cpp
/// \brief File access for the OBJ loader: read the whole file at once and, when it starts
/// with the gzip magic bytes, inflate it in memory with zlib before parsing.
#include "input_file.h"
#include <nori/objloader.h>
#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

namespace nori {
namespace {

/// OBJ text (plain, or after decompression) beyond this is refused: ~60 million triangles.
constexpr size_t MaxObjText = size_t(4) << 30;

bool isGzip(const std::string &data) {
    return data.size() >= 2 && (unsigned char) data[0] == 0x1f && (unsigned char) data[1] == 0x8b;
}

[[noreturn]] void corruptGzip(const std::string &path, const z_stream &zs) {
    if (zs.msg) throw NoriException("{}: corrupt gzip data ({})", path, zs.msg);
    throw NoriException("{}: corrupt gzip data", path);
}

/// Inflate a complete .gz file (possibly several concatenated members, like `gzip -dc`).
std::string gunzip(const std::string &in, const std::string &path) {
    // The gzip trailer's size claim is not trusted (a truncated or hostile file can claim 4 GB):
    // the buffer grows as data arrives, up to what the file can hold. Deflate expands at most
    // ~1032:1 (RFC 1951: a 258-byte match per ~2 bits), for each member as for all of them.
    const size_t limit = std::min(in.size() * 1032 + 1024, MaxObjText);
    std::string out;
    out.resize(std::min(limit, std::max<size_t>(in.size() * 4, size_t(1) << 16)));

    z_stream zs{};
    if (inflateInit2(&zs, 15 + 16) != Z_OK) throw NoriException("{}: cannot initialise zlib", path);
    struct InflateGuard {
        z_stream *zs;
        ~InflateGuard() { inflateEnd(zs); }
    } guard{&zs};

    const unsigned char *next = reinterpret_cast<const unsigned char *>(in.data());
    size_t left = in.size(), produced = 0;
    const size_t chunk = size_t(1) << 30; // z_stream counters are 32-bit
    for (;;) {
        if (produced == out.size()) {
            if (out.size() >= limit)
                throw NoriException("{}: the mesh decompresses to more than {} MiB (the limit for {} bytes of gzip data)",
                                    path, limit >> 20, in.size());
            try {
                out.resize(std::min(limit, out.size() * 2));
            } catch (const std::bad_alloc &) {
                throw NoriException("{}: out of memory while decompressing ({} MiB so far)", path, produced >> 20);
            }
        }
        zs.next_in = const_cast<unsigned char *>(next);
        zs.avail_in = uInt(std::min(left, chunk));
        zs.next_out = reinterpret_cast<unsigned char *>(&out[produced]);
        zs.avail_out = uInt(std::min(out.size() - produced, chunk));
        const uInt inBefore = zs.avail_in, outBefore = zs.avail_out;
        int ret = inflate(&zs, Z_NO_FLUSH);
        next += inBefore - zs.avail_in;
        left -= inBefore - zs.avail_in;
        produced += outBefore - zs.avail_out;

        if (ret == Z_STREAM_END) {
            // Another member follows, or zero padding, or trailing junk.
            if (left >= 2 && next[0] == 0x1f && next[1] == 0x8b) {
                inflateReset(&zs);
                continue;
            }
            if (std::all_of(next, next + left, [](unsigned char c) { return c == 0; })) break;
            throw NoriException("{}: corrupt gzip data (trailing garbage)", path);
        }
        if (ret == Z_MEM_ERROR) throw NoriException("{}: out of memory while decompressing", path);
        if (ret == Z_BUF_ERROR && produced < out.size()) corruptGzip(path, zs); // truncated
        if (ret != Z_OK && ret != Z_BUF_ERROR) corruptGzip(path, zs);
    }
    out.resize(produced);
    return out;
}

} // namespace

MeshData loadObjFile(const std::string &path) {
    std::string data = readInputFile(path, "mesh file", MaxObjText);
    if (isGzip(data)) data = gunzip(data, path);
    MeshData mesh;
    try {
        mesh = parseObj(data, path);
    } catch (const std::bad_alloc &) {
        throw NoriException("{}: out of memory reading the mesh", path);
    }
    // Prose, or an OBJ of points and lines only: an empty mesh would render as a silent black image.
    if (mesh.faces.empty()) throw NoriException("{}: no triangles (no 'f' statement with 3 or more vertices)", path);
    return mesh;
}

} // namespace nori
