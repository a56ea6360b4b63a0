/// \file atomic_file.cpp
/// \brief AtomicFile: temporary file in the same folder, fsync, rename.
#include <nori/atomic_file.h>
#include <nori/common.h>

#include <atomic>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

namespace nori {

namespace {
/// Distinguishes the temporary files of concurrent writes to one path within one process.
std::atomic<unsigned> g_temporaryCounter{0};

/// The temporary files that exist now, in fixed storage that a signal handler can read.
constexpr int SlotCount = 16;
char g_slotPath[SlotCount][PATH_MAX];
std::atomic<bool> g_slotUsed[SlotCount];

int registerTemporary(const std::string &path) {
    if (path.size() >= PATH_MAX) return -1;  // open() has failed for such a name already
    for (int i = 0; i < SlotCount; ++i) {
        if (g_slotUsed[i].load()) continue;
        std::memcpy(g_slotPath[i], path.c_str(), path.size() + 1);
        bool expected = false;
        if (g_slotUsed[i].compare_exchange_strong(expected, true)) return i;
    }
    return -1;  // more than SlotCount at once: only the destructor cleans those up
}
} // namespace

void AtomicFile::removeTemporariesNow() noexcept {
    for (int i = 0; i < SlotCount; ++i)
        if (g_slotUsed[i].load()) ::unlink(g_slotPath[i]);
}

AtomicFile::AtomicFile(std::string path) : m_path(std::move(path)) {
    m_temporary = fmt::format("{}.tmp-{}-{}", m_path, long(::getpid()), g_temporaryCounter.fetch_add(1));
    // O_EXCL: never clobber (or follow a symbolic link planted at) an existing file of that name.
    m_fd = ::open(m_temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (m_fd < 0) {
        m_done = true;  // nothing was created
        throw NoriException("{}: cannot write: cannot create '{}': {}", m_path, m_temporary, std::strerror(errno));
    }
    m_slot = registerTemporary(m_temporary);
}

AtomicFile::AtomicFile(AtomicFile &&other) noexcept
    : m_path(std::move(other.m_path)), m_temporary(std::move(other.m_temporary)), m_fd(other.m_fd),
      m_slot(other.m_slot), m_done(other.m_done) {
    other.m_fd = -1;
    other.m_slot = -1;
    other.m_done = true;
}

AtomicFile::~AtomicFile() { discard(); }

void AtomicFile::discard() noexcept {
    if (m_fd >= 0) ::close(m_fd);
    m_fd = -1;
    if (!m_done) ::unlink(m_temporary.c_str());
    m_done = true;
    release();
}

void AtomicFile::release() noexcept {
    if (m_slot >= 0) g_slotUsed[m_slot].store(false);
    m_slot = -1;
}

void AtomicFile::fail(const std::string &what, int error) {
    discard();
    throw NoriException("{}: cannot write: {} '{}': {}", m_path, what, m_temporary, std::strerror(error));
}

void AtomicFile::write(std::string_view bytes) {
    if (m_fd < 0) throw NoriException("{}: cannot write: the file is already closed", m_path);
    const char *data = bytes.data();
    size_t remaining = bytes.size();
    while (remaining > 0) {
        ssize_t written = ::write(m_fd, data, remaining);
        if (written < 0) {
            if (errno == EINTR) continue;
            fail("cannot write", errno);
        }
        data += written;
        remaining -= size_t(written);
    }
}

void AtomicFile::finish() {
    if (m_fd < 0) return;
    // Without fsync a crash right after rename() could leave an empty file under the final name.
    if (::fsync(m_fd) != 0) fail("cannot flush", errno);
    int fd = m_fd;
    m_fd = -1;
    if (::close(fd) != 0) fail("cannot close", errno);
}

void AtomicFile::commit() {
    if (m_done) throw NoriException("{}: cannot write: the file was discarded", m_path);
    finish();
    if (::rename(m_temporary.c_str(), m_path.c_str()) != 0) fail("cannot rename", errno);
    m_done = true;
    release();
}

void AtomicFile::write(const std::string &path, std::string_view bytes) {
    AtomicFile file(path);
    file.write(bytes);
    file.commit();
}

} // namespace nori
