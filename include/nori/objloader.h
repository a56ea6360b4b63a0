/// \file objloader.h
/// \brief Wavefront OBJ reader (plain or gzip-compressed) producing MeshData.
#pragma once

#include <nori/mesh.h>
#include <string>
#include <string_view>

namespace nori {

/// \brief Load an OBJ file (or a gzip-compressed one, detected by its magic bytes) into MeshData.
///
/// Reads `v`, `vt`, `vn` and `f` statements; every other statement is ignored. Polygons are
/// fan-triangulated. Normals / uvs are returned only when every face corner references one.
/// \throws NoriException with a one-line message "FILE:LINE: what is wrong" (or
///         "FILE: what is wrong" for I/O and decompression errors).
MeshData loadObjFile(const std::string &path);

/// \brief Parse OBJ text that is already in memory; \p name is used in error messages.
/// \throws NoriException on malformed input, see loadObjFile().
MeshData parseObj(std::string_view text, const std::string &name);

} // namespace nori
