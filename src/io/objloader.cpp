/// \file objloader.cpp
/// \brief File access for the OBJ loader: read the whole file at once and, when it starts
/// with the gzip magic bytes, inflate it in memory with zlib before parsing.
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

/// Closes a file descriptor on every exit path.
struct FdGuard {
    int fd;
    ~FdGuard() {
        if (fd >= 0) ::close(fd);
    }
};

/// The whole file in one buffer (regular files: a single allocation of the right size).
std::string readWholeFile(const std::string &path) {
    FdGuard f{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
    if (f.fd < 0) throw NoriException("{}: cannot open: {}", path, std::strerror(errno));
    struct stat st {};
    if (::fstat(f.fd, &st) != 0) throw NoriException("{}: cannot open: {}", path, std::strerror(errno));
    if (S_ISDIR(st.st_mode)) throw NoriException("{}: cannot open: {}", path, std::strerror(EISDIR));
    // A device such as /dev/zero or /dev/urandom never ends: reading it would exhaust memory.
    if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode))
        throw NoriException("{}: cannot open: is a device, not a mesh file", path);

    std::string buf;
    // Regular files: read exactly their size (+1 to notice growth); pipes etc.: grow as needed.
    buf.resize(S_ISREG(st.st_mode) ? size_t(st.st_size) + 1 : size_t(1) << 16);
    size_t used = 0;
    for (;;) {
        if (used == buf.size()) buf.resize(buf.size() * 2);
        ssize_t got = ::read(f.fd, &buf[used], std::min<size_t>(buf.size() - used, size_t(1) << 30));
        if (got < 0) {
            if (errno == EINTR) continue;
            throw NoriException("{}: cannot read: {}", path, std::strerror(errno));
        }
        if (got == 0) break;
        used += size_t(got);
    }
    buf.resize(used);
    return buf;
}

bool isGzip(const std::string &data) {
    return data.size() >= 2 && (unsigned char) data[0] == 0x1f && (unsigned char) data[1] == 0x8b;
}

[[noreturn]] void corruptGzip(const std::string &path, const z_stream &zs) {
    if (zs.msg) throw NoriException("{}: corrupt gzip data ({})", path, zs.msg);
    throw NoriException("{}: corrupt gzip data", path);
}

/// Inflate a complete .gz file (possibly several concatenated members, like `gzip -dc`).
std::string gunzip(const std::string &in, const std::string &path) {
    // The gzip trailer stores the uncompressed size mod 2^32: a good first allocation. It is
    // only a claim of the file, though: deflate expands at most ~1032:1, so a larger claim
    // (a corrupt or hostile trailer) must not reserve gigabytes for a few bytes of input.
    size_t hint = in.size() * 4;
    if (in.size() >= 18) {
        const unsigned char *t = reinterpret_cast<const unsigned char *>(in.data() + in.size() - 4);
        hint = size_t(t[0]) | size_t(t[1]) << 8 | size_t(t[2]) << 16 | size_t(t[3]) << 24;
    }
    hint = std::min(hint, in.size() * 1032 + 1024);
    std::string out;
    out.resize(std::max<size_t>(hint, 1 << 16) + 1);

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
        if (produced == out.size()) out.resize(out.size() * 2);
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
    std::string data = readWholeFile(path);
    if (isGzip(data)) data = gunzip(data, path);
    return parseObj(data, path);
}

} // namespace nori
