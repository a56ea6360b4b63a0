/// \file input_file.h
/// \brief Reads a whole input file (scene or mesh) without ever blocking or growing without bound.
#pragma once

#include <cstddef>
#include <string>

namespace nori {

/// \brief The whole content of the regular file \p path. Anything else is refused before it is
/// opened (a FIFO or a device could block or never end): "PATH: cannot open: is a FIFO (named
/// pipe), not a KIND", where KIND is \p kind ("scene file", "mesh file"). A file larger than
/// \p maxBytes, and a failed allocation, are errors naming the file.
std::string readInputFile(const std::string &path, const char *kind, size_t maxBytes);

/// \brief What stands at \p path when it is not a regular file ("a FIFO (named pipe)", ...),
/// or an empty string for a regular file or one that does not exist.
std::string describeSpecialFile(const std::string &path);

} // namespace nori
