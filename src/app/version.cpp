/// \file version.cpp
/// \brief versionString() from the header that cmake/version.cmake generates at build time.
#include "version.h"
#include <version_info.h>

namespace nori {

std::string versionString() {
    std::string commit = NORI_GIT_COMMIT;
    return commit.empty() ? std::string(NORI_VERSION) : std::string(NORI_VERSION) + " (git " + commit + ")";
}

} // namespace nori
