/// \file cli_app.cpp
/// \brief CliApp: CLI11 with the project's help, version and error conventions.
#include "cli_app.h"
#include "version.h"
#include <charconv>
#include <cstdio>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <set>

namespace nori {

CliApp::CliApp(std::string program, const std::string &description)
    : m_program(std::move(program)), m_app(description, m_program) {
    m_app.set_help_flag("-h,--help", "show this help and exit");
    m_app.set_version_flag("--version", m_program + " " + versionString(), "show the version (and git commit) and exit");
    m_app.get_formatter()->column_width(30);
    // Options come before or after the positional arguments; "--" ends the options.
    m_app.positionals_at_end(false);
}

std::optional<int> CliApp::parse(int argc, const char *const *argv, const std::function<void()> &finish) {
    try {
        m_app.parse(argc, argv);
        if (finish) finish();
    } catch (const CLI::CallForHelp &) {
        std::fputs(m_app.help().c_str(), stdout);
        return 0;
    } catch (const CLI::CallForVersion &e) {
        std::printf("%s\n", e.what());
        return 0;
    } catch (const CLI::ParseError &e) {
        return usageError(e.what());
    } catch (const UsageError &e) {  // thrown by finish() or an option's callback
        return usageError(e.what());
    }
    return std::nullopt;
}

int CliApp::usageError(const std::string &message) const {
    std::fprintf(stderr, "%s: %s (see --help)\n", m_program.c_str(), oneLine(message).c_str());
    return UsageStatus;
}

std::string oneLine(std::string text) {
    for (char &c : text)
        if ((unsigned char)c < 0x20 || c == 0x7f) c = ' ';
    return text;
}

CLI::Validator integerIn(long long lo, long long hi) {
    return CLI::Validator(
        [lo, hi](std::string &text) -> std::string {
            long long value = 0;
            auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
            if (ec != std::errc() || end != text.data() + text.size() || value < lo || value > hi)
                return fmt::format("expected an integer in [{}, {}], got '{}'", lo, hi, text);
            return {};
        },
        "", "integerIn");
}

CLI::Validator oneOf(const std::vector<std::string> &choices) {
    return CLI::Validator(
        [choices](std::string &text) -> std::string {
            for (const std::string &c : choices)
                if (c == text) return {};
            return fmt::format("unknown value '{}' (expected one of: {})", text, fmt::join(choices, ", "));
        },
        "", "oneOf");
}

std::vector<std::string> splitList(const std::string &text) {
    std::vector<std::string> items;
    size_t start = 0;
    for (;;) {
        size_t comma = text.find(',', start);
        items.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
        if (comma == std::string::npos) return items;
        start = comma + 1;
    }
}

CLI::Validator listOf(const CLI::Validator &item) {
    return CLI::Validator(
        [item](std::string &text) -> std::string {
            std::set<std::string> seen;
            for (std::string value : splitList(text)) {
                if (value.empty()) return fmt::format("empty item in list '{}'", text);
                if (!seen.insert(value).second) return fmt::format("'{}' listed twice", value);
                std::string error = item(value);
                if (!error.empty()) return error;
            }
            return {};
        },
        "", "listOf");
}

} // namespace nori
