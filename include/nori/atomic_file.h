/// \file atomic_file.h
/// \brief The one way every tool writes an output file: readers see the old file or the whole new one.
#pragma once

#include <string>
#include <string_view>

namespace nori {

/// \brief An output file being written: the bytes go to a temporary file in the target's folder
/// (so that the final rename() stays within one file system and is atomic), are flushed to the
/// disk (fsync), and replace the target only in commit(). Destroying an uncommitted AtomicFile
/// removes its temporary file and leaves the target as it was.
///
/// Every failure throws NoriException("PATH: cannot write: reason").
class AtomicFile {
public:
    /// \brief Create the temporary file "PATH.tmp-PID-N" beside \p path (never an existing file).
    explicit AtomicFile(std::string path);
    ~AtomicFile();
    AtomicFile(AtomicFile &&other) noexcept;
    AtomicFile &operator=(AtomicFile &&) = delete;
    AtomicFile(const AtomicFile &) = delete;
    AtomicFile &operator=(const AtomicFile &) = delete;

    /// \brief Append \p bytes to the temporary file.
    void write(std::string_view bytes);
    /// \brief Flush the data to the disk and close the temporary file; only commit() may follow.
    void finish();
    /// \brief finish() if needed, then rename the temporary file over the target.
    void commit();
    /// \brief Remove the temporary file now (the destructor does it too).
    void discard() noexcept;

    /// \brief The target.
    const std::string &path() const { return m_path; }
    /// \brief The temporary file's name.
    const std::string &temporaryPath() const { return m_temporary; }

    /// \brief Write \p bytes to \p path in one step: construct, write, commit.
    static void write(const std::string &path, std::string_view bytes);

    /// \brief Remove every temporary file of this process that is not committed yet. Only
    /// async-signal-safe calls: for a signal handler that is about to end the process.
    static void removeTemporariesNow() noexcept;

private:
    [[noreturn]] void fail(const std::string &what, int error);
    void release() noexcept;

    std::string m_path, m_temporary;
    int m_fd = -1;
    int m_slot = -1;      ///< in the registry removeTemporariesNow() reads
    bool m_done = false;  ///< renamed or discarded: nothing left to clean up
};

} // namespace nori
