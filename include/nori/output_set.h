/// \file output_set.h
/// \brief Several output files written as one transaction: all of them replace their targets, or none does.
#pragma once

#include <nori/atomic_file.h>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace nori {

/// \brief The outputs of one run (e.g. EXR, PNG and statistics). add() writes each to a
/// temporary file beside its target and flushes it to the disk; commit() renames them all,
/// holding an exclusive lock (flock) on each target folder so that concurrent runs writing
/// the same names never leave a mixed set. Destroying an uncommitted set removes its temporaries.
class OutputSet {
public:
    /// \brief Refuse, before any work is done, paths that could not all be written: an empty
    /// name, a name that is a folder or ends in '/', a folder that is missing or not writable,
    /// an existing target that is not a regular file, or two outputs on one path. Throws
    /// NoriException naming the path.
    static void check(const std::vector<std::string> &paths);

    /// \brief Write \p bytes for \p path to a temporary file (flushed to the disk).
    void add(const std::string &path, std::string_view bytes);

    /// \brief Rename every temporary file over its target. \p afterRename (a test hook) runs
    /// after each rename, with the folders still locked.
    void commit(const std::function<void(const std::string &path)> &afterRename = {});

    /// \brief The targets added so far.
    std::vector<std::string> paths() const;

private:
    std::vector<AtomicFile> m_files;
};

} // namespace nori
