/// \file resolver.h
/// \brief Finds the files a scene refers to: scene folder first, then the `-a` search path.
#pragma once

#include <string>
#include <vector>

namespace nori {

/// \brief Ordered list of folders in which relative file names are looked up.
class FileResolver {
public:
    /// \brief Add a folder at the front (searched first) or at the back.
    void prepend(const std::string &folder);
    void append(const std::string &folder);
    /// \brief Remove the first folder (undoes prepend()).
    void popFront();
    /// \brief Absolute names are returned as they are; relative ones are joined with the
    /// first folder in which they exist. If none has them, the name joined with the first
    /// folder is returned, so the caller's "cannot open" message shows a sensible path.
    std::string resolve(const std::string &name) const;
    const std::vector<std::string> &folders() const { return m_folders; }

private:
    std::vector<std::string> m_folders;
};

/// \brief The resolver used while loading scenes (one per process, like Nori's).
FileResolver &fileResolver();

} // namespace nori
