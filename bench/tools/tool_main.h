/// \file tool_main.h
/// \brief The main() of the bench's small tools: a thrown error (a bad scene or mesh) becomes
/// one line on stderr and exit status 1, not an abort.
#pragma once

#include "../heap_policy.h"
#include <cstdio>
#include <exception>

namespace nori::bench {

/// Runs \p run(argc, argv) and returns its status, or 1 after printing what it threw.
template <typename Run>
int toolMain(int argc, char **argv, Run run) {
    keepFreedMemoryForReuse();
    try {
        return run(argc, argv);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}

} // namespace nori::bench
