// Write-to-temporary-then-rename, so that a failed or interrupted write never leaves a
// half-written output under the final name. A process killed mid-write leaves its temporary
// (core/temporary_files.h); the next output written into that folder removes it.
#pragma once

#include "core/temporary_files.h"

#include <string>

namespace lh {

class AtomicOutput {
public:
    // Creates an empty temporary file next to `finalPath` (same directory, so rename is
    // atomic), after removing the temporaries that killed processes left in that directory
    // (removeAbandonedTemporaries). Throws FileError if the directory does not exist or
    // cannot be written, naming the reason (permission denied, read-only file system, ...)
    // before any work is done.
    explicit AtomicOutput(std::string finalPath);
    ~AtomicOutput();  // removes the temporary file unless commit() succeeded
    AtomicOutput(const AtomicOutput&) = delete;
    AtomicOutput& operator=(const AtomicOutput&) = delete;

    // Where the writer should write.
    const std::string& tempPath() const { return tempPath_; }
    const std::string& finalPath() const { return finalPath_; }
    // Renames the temporary file onto the final path. Throws FileError on failure.
    void commit();

private:
    std::string finalPath_;
    std::string tempPath_;
    bool committed_ = false;
};

// Throws FileError, with the reason, unless a file can be created in `path`'s folder: lets a
// long command (predict, say) fail before its work rather than after it.
void requireWritableOutput(const std::string& path);

// Writes `text` plus a newline to `path` atomically. Throws FileError.
void writeTextFile(const std::string& path, const std::string& text);

// Lower-cased extension including the dot (".exr"), or "" if none.
std::string fileExtension(const std::string& path);

}  // namespace lh
