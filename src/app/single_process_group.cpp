/// \file single_process_group.cpp
/// \brief ProcessGroup::join() of a build without MPI (NORI_MPI off): always one process.
#include "process_group.h"

namespace nori {

std::unique_ptr<ProcessGroup> ProcessGroup::join(int &, char **&) { return nullptr; }

} // namespace nori
