/// \file atomic_file.h
/// \brief Writes an output file so that readers never see it half-written.
#pragma once

#include <string>

namespace nori::bench {

class AtomicFile {
public:
    /// \brief Write \p content to a temporary file next to \p path, then rename it over
    /// \p path. Creates missing parent folders. Throws NoriException on failure.
    static void write(const std::string &path, const std::string &content);
};

} // namespace nori::bench
