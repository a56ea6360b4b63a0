/// \file resolver.cpp
/// \brief Finds the files a scene refers to: scene folder first, then the `-a` search path (implementation).
#include <nori/resolver.h>
#include <filesystem>

namespace nori {

namespace fs = std::filesystem;

void FileResolver::prepend(const std::string &folder) { m_folders.insert(m_folders.begin(), folder); }
void FileResolver::append(const std::string &folder) { m_folders.push_back(folder); }
void FileResolver::popFront() {
    if (!m_folders.empty()) m_folders.erase(m_folders.begin());
}

std::string FileResolver::resolve(const std::string &name) const {
    fs::path path(name);
    if (path.is_absolute()) return name;
    std::error_code ec;
    for (const std::string &folder : m_folders) {
        fs::path candidate = fs::path(folder) / path;
        if (fs::exists(candidate, ec)) return candidate.string();
    }
    return m_folders.empty() ? name : (fs::path(m_folders.front()) / path).string();
}

FileResolver &fileResolver() {
    static FileResolver instance;
    return instance;
}

} // namespace nori
