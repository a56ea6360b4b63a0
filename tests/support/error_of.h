/// \file error_of.h
/// \brief The message of the exception a test expects.
#pragma once

#include <gtest/gtest.h>
#include <nori/common.h>
#include <string>

namespace nori {

/// \brief The message of the NoriException thrown by \p f; fails the test when nothing is thrown.
template <typename F> std::string errorOf(F &&f) {
    try {
        f();
    } catch (const NoriException &e) {
        return e.what();
    }
    ADD_FAILURE() << "no NoriException thrown";
    return {};
}

} // namespace nori
