/// \file output_set.cpp
/// \brief OutputSet: path checks before the work, temporaries, and renames under folder locks.
#include <nori/common.h>
#include <nori/output_set.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <memory>
#include <set>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace nori {

namespace fs = std::filesystem;

namespace {

/// The folder a path's file lives in ("." for a bare name).
fs::path folderOf(const std::string &path) {
    fs::path folder = fs::path(path).parent_path();
    return folder.empty() ? fs::path(".") : folder;
}

/// Holds flock(LOCK_EX) on one folder until destroyed.
class FolderLock {
public:
    explicit FolderLock(const fs::path &folder) {
        m_fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
        if (m_fd < 0) throw NoriException("{}: cannot lock the output folder: {}", folder.string(), std::strerror(errno));
        while (::flock(m_fd, LOCK_EX) != 0) {
            if (errno == EINTR) continue;
            int error = errno;
            ::close(m_fd);
            throw NoriException("{}: cannot lock the output folder: {}", folder.string(), std::strerror(error));
        }
    }
    ~FolderLock() { ::close(m_fd); }  // closing releases the lock
    FolderLock(const FolderLock &) = delete;
    FolderLock &operator=(const FolderLock &) = delete;

private:
    int m_fd = -1;
};

} // namespace

void OutputSet::check(const std::vector<std::string> &paths) {
    std::set<std::string> seen;
    for (const std::string &path : paths) {
        if (path.empty()) throw NoriException("an output file name is empty");
        if (path.back() == '/') throw NoriException("{}: an output file name cannot end in '/'", path);
        std::string name = fs::path(path).filename().string();
        if (name == "." || name == "..") throw NoriException("{}: not a file name", path);
        fs::path folder = folderOf(path);
        std::error_code ec;
        if (!fs::is_directory(folder, ec)) throw NoriException("{}: output folder does not exist", folder.string());
        if (::access(folder.c_str(), W_OK | X_OK) != 0)
            throw NoriException("{}: output folder is not writable: {}", folder.string(), std::strerror(errno));
        struct stat st {};
        if (::stat(path.c_str(), &st) == 0) {
            if (S_ISDIR(st.st_mode)) throw NoriException("{}: is a folder, cannot write the output there", path);
            if (!S_ISREG(st.st_mode)) throw NoriException("{}: is not a regular file, cannot replace it", path);
        }
        // Two names for one file (a/x.exr and a/../a/x.exr): compare the resolved paths.
        std::string key = fs::weakly_canonical(fs::absolute(path), ec).string();
        if (ec) key = fs::absolute(path).lexically_normal().string();
        if (!seen.insert(key).second) throw NoriException("{}: given for two outputs at once", path);
    }
    // An output named like another one's temporary file ("x.exr.tmp-...") would be overwritten by it.
    for (const std::string &a : seen)
        for (const std::string &b : seen)
            if (b.size() > a.size() && b.compare(0, a.size() + 5, a + ".tmp-") == 0)
                throw NoriException("{}: named like the temporary file of the output {}", b, a);
}

void OutputSet::add(const std::string &path, std::string_view bytes) {
    AtomicFile file(path);
    file.write(bytes);
    file.finish();
    m_files.push_back(std::move(file));
}

void OutputSet::commit(const std::function<void(const std::string &path)> &afterRename) {
    // Lock every target folder, always in the same (sorted) order so that two runs cannot deadlock.
    std::set<std::string> folders;
    for (const AtomicFile &file : m_files) {
        std::error_code ec;
        fs::path folder = fs::weakly_canonical(fs::absolute(folderOf(file.path())), ec);
        folders.insert(ec ? folderOf(file.path()).string() : folder.string());
    }
    std::vector<std::unique_ptr<FolderLock>> locks;
    for (const std::string &folder : folders) locks.push_back(std::make_unique<FolderLock>(folder));
    for (AtomicFile &file : m_files) {
        file.commit();
        if (afterRename) afterRename(file.path());
    }
    m_files.clear();
}

std::vector<std::string> OutputSet::paths() const {
    std::vector<std::string> result;
    for (const AtomicFile &file : m_files) result.push_back(file.path());
    return result;
}

} // namespace nori
