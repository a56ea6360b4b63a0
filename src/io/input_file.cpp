/// \file input_file.cpp
/// \brief readInputFile(): stat before open, O_NONBLOCK, exact-size reads, bounded size.
#include "input_file.h"
#include <nori/common.h>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <new>
#include <sys/stat.h>
#include <unistd.h>

namespace nori {

namespace {

/// Empty for a regular file; otherwise what the file is, for the message.
std::string describe(const struct stat &st) {
    if (S_ISREG(st.st_mode)) return {};
    if (S_ISDIR(st.st_mode)) return "Is a directory";
    if (S_ISFIFO(st.st_mode)) return "is a FIFO (named pipe)";
    if (S_ISSOCK(st.st_mode)) return "is a socket";
    if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "is a device";
    return "is not a regular file";
}

struct FdGuard {
    int fd;
    ~FdGuard() {
        if (fd >= 0) ::close(fd);
    }
};

std::string megabytes(size_t bytes) { return fmt::format("{:.0f} MiB", double(bytes) / (1024.0 * 1024.0)); }

} // namespace

std::string describeSpecialFile(const std::string &path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return {};
    return describe(st);
}

std::string readInputFile(const std::string &path, const char *kind, size_t maxBytes) {
    // stat() first: open() itself blocks on a FIFO that has no writer.
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) throw NoriException("{}: cannot open: {}", path, std::strerror(errno));
    std::string what = describe(st);
    if (!what.empty()) throw NoriException("{}: cannot open: {}, not a {}", path, what, kind);
    // O_NONBLOCK: should the name be swapped for a FIFO in between, open() still returns at once.
    FdGuard f{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
    if (f.fd < 0) throw NoriException("{}: cannot open: {}", path, std::strerror(errno));
    if (::fstat(f.fd, &st) != 0) throw NoriException("{}: cannot open: {}", path, std::strerror(errno));
    what = describe(st);
    if (!what.empty()) throw NoriException("{}: cannot open: {}, not a {}", path, what, kind);
    if (size_t(st.st_size) > maxBytes)
        throw NoriException("{}: the {} is larger than {} (the limit)", path, kind, megabytes(maxBytes));

    std::string buffer;
    try {
        buffer.resize(size_t(st.st_size) + 1);  // +1 notices a file that grows while it is read
    } catch (const std::bad_alloc &) {
        throw NoriException("{}: out of memory reading the {} ({})", path, kind, megabytes(size_t(st.st_size)));
    }
    size_t used = 0;
    while (used < buffer.size()) {
        ssize_t got = ::read(f.fd, &buffer[used], buffer.size() - used);
        if (got < 0) {
            if (errno == EINTR) continue;
            throw NoriException("{}: cannot read: {}", path, std::strerror(errno));
        }
        if (got == 0) break;
        used += size_t(got);
    }
    if (used > size_t(st.st_size)) throw NoriException("{}: the {} changed while it was read", path, kind);
    buffer.resize(used);
    return buffer;
}

} // namespace nori
