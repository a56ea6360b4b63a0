/// \file version.h
/// \brief The version every tool prints for --version.
#pragma once

#include <string>

namespace nori {

/// \brief "X.Y.Z" from CMake's project(VERSION), plus " (git COMMIT)" when built from a checkout.
std::string versionString();

} // namespace nori
