#pragma once
// The one way the project writes a file it owns (images, stats, reports, the registry, the
// pipeline cache): a reader never sees half a file, a failure never harms the file that was
// there, and nothing is left behind.
//
// How: the bytes go to an unnamed temporary in the target's folder (Linux O_TMPFILE; a process
// killed mid-write, even by SIGKILL, leaves nothing), every write, the fsync and the close are
// checked, and only then is the file given a temporary name and renamed over the target
// (rename() within one folder is atomic on POSIX). Where the file system has no O_TMPFILE, a
// named temporary `<stem>.tmp-<pid>-<n><ext>` is used instead: a SIGINT or SIGTERM while it
// exists removes it (TemporaryGuard), and one left by a SIGKILLed writer (its process gone) is
// removed by the next write of the same target.
//
// Errors are one line: `<file>: <what failed>: <strerror>` (the target, never the temporary).

#include <filesystem>
#include <string_view>

#include "core/result.hpp"

namespace acetate {

// A temporary name next to `file`, unique within this process: `<stem>.tmp-<pid>-<n><ext>`.
// The extension stays last so that the name still says what the file holds.
std::filesystem::path temp_sibling(const std::filesystem::path& file);

// Writes `bytes` to `file` atomically. On failure `file` is untouched and no temporary is left
// behind. An existing `file` that is not a regular file (a folder, a device, a FIFO) is refused
// rather than replaced.
Result<void> write_file_atomically(const std::filesystem::path& file, std::string_view bytes);

// Removes the named temporaries of `file` (`<stem>.tmp-<pid>-<n><ext>`) whose writing process
// no longer exists. Temporaries of live processes are left alone.
void remove_dead_writers_temporaries(const std::filesystem::path& file);

}  // namespace acetate
