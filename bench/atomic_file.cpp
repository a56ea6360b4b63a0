#include "atomic_file.h"
#include <nori/common.h>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <unistd.h>

namespace nori::bench {

void AtomicFile::write(const std::string &path, const std::string &content) {
    namespace fs = std::filesystem;
    fs::path target(path);
    std::error_code ec;
    if (target.has_parent_path()) fs::create_directories(target.parent_path(), ec);
    if (ec) throw NoriException("{}: cannot create folder {}: {}", path, target.parent_path().string(), ec.message());
    std::string tmp = fmt::format("{}.tmp.{}", path, long(getpid()));
    FILE *f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw NoriException("{}: cannot write: {}", tmp, std::strerror(errno));
    size_t written = std::fwrite(content.data(), 1, content.size(), f);
    bool ok = written == content.size() && std::fflush(f) == 0 && fsync(fileno(f)) == 0;
    ok = (std::fclose(f) == 0) && ok;
    if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0) {
        int err = errno;
        std::remove(tmp.c_str());
        throw NoriException("{}: cannot write: {}", path, std::strerror(err));
    }
}

} // namespace nori::bench
