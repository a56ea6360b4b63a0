/// \file cli_app.h
/// \brief The command-line conventions of every nori tool, on top of CLI11.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace nori {

/// \brief A mistake on the command line found after parsing (e.g. two options that do not go
/// together). The tool prints it like a parse error: one line, exit status CliApp::UsageStatus.
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// \brief A CLI11 application with the project's conventions: `--opt=value`, `-t2`, `--`
/// before a file name starting with '-', `--version`, `--help` grouped by topic, and every
/// usage error as one line "PROGRAM: message (see --help)" with exit status 2.
class CliApp {
public:
    static constexpr int UsageStatus = 2;

    CliApp(std::string program, const std::string &description);

    /// \brief The CLI11 app, to declare options on.
    CLI::App &app() { return m_app; }

    /// \brief Parse \p argc / \p argv, then run \p finish (the checks across options, which
    /// may throw UsageError). Returns the exit status when the tool should stop now (0 after
    /// --help or --version, which were printed on stdout; UsageStatus after a usage error,
    /// which was printed on stderr), or nothing when it should go on.
    std::optional<int> parse(int argc, const char *const *argv, const std::function<void()> &finish = {});

    /// \brief Print "PROGRAM: \p message (see --help)" on one line of stderr; returns UsageStatus.
    int usageError(const std::string &message) const;

    /// \brief The --help text.
    std::string help() const { return m_app.help(); }

private:
    std::string m_program;
    CLI::App m_app;
};

/// \brief \p text on one line: line breaks and other control characters become spaces.
std::string oneLine(std::string text);

/// \brief Accepts a whole decimal integer in [lo, hi]; the message says so and echoes the text.
CLI::Validator integerIn(long long lo, long long hi);

/// \brief Accepts one of \p choices; the message lists them.
CLI::Validator oneOf(const std::vector<std::string> &choices);

/// \brief Accepts a comma-separated list of distinct non-empty items, each accepted by \p item.
CLI::Validator listOf(const CLI::Validator &item);

/// \brief The items of a comma-separated list (already checked by listOf()).
std::vector<std::string> splitList(const std::string &text);

} // namespace nori
