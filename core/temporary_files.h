// Temporaries written beside an output before it is renamed into place, and the removal of
// those that a killed process left behind.
//
// A temporary is named "DIR/.STEM.KIND<pid>_<n>_<host>EXT": hidden (every reader of this
// project skips dot files), unique per process and call, within kMaxFileNameBytes, and it
// names the process and the machine that made it. A later run can therefore tell a temporary
// abandoned by a process that was killed mid-write (SIGKILL, the OOM killer: no destructor
// ran) from one that a live writer is still filling, on this machine or, over a shared file
// system, on another one.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace lh {

// NAME_MAX of Linux file systems (ext4, xfs, tmpfs): bytes in one path component.
constexpr std::size_t kMaxFileNameBytes = 255;

// A fresh temporary name in the folder of `finalPath` (so that renaming it onto `finalPath` is
// atomic). `kind` is a short word ("tmp": being written; "old": being removed). With
// `keepExtension`, the temporary ends with `finalPath`'s extension (some writers choose the
// format by it); the stem is shortened as needed to keep the name within kMaxFileNameBytes.
std::string temporaryBeside(const std::string& finalPath, const std::string& kind,
                            bool keepExtension = true);

// Removes the temporaries in `folder` ("" is the current folder) that processes of this
// machine left behind and that no longer run: files and folders alike. Runs once per process
// and folder (a process's own temporaries are never stale); a temporary of a live process, or
// of another machine, is left alone, and one that cannot be removed is left too (it is only
// clutter).
void removeAbandonedTemporaries(const std::string& folder);

// Who made a temporary, from its file name; nullopt if `fileName` is not one.
struct TemporaryOwner {
    long pid = 0;
    std::string host;  // thisHostTag() of the machine that made it
};
std::optional<TemporaryOwner> temporaryOwner(const std::string& fileName);

// 8 hexadecimal digits that name this machine (a hash of its host name).
const std::string& thisHostTag();

}  // namespace lh
