#include "core/atomic_file.h"

#include "core/errors.h"

#include <fcntl.h>
#include <unistd.h>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

namespace lh {

namespace fs = std::filesystem;

AtomicOutput::AtomicOutput(std::string finalPath) : finalPath_(std::move(finalPath)) {
    if (finalPath_.empty()) throw FileError("output path is empty");
    fs::path p(finalPath_);
    fs::path dir = p.parent_path();
    if (!dir.empty() && !fs::is_directory(dir))
        throw FileError("cannot write '" + finalPath_ + "': directory '" + dir.string() +
                        "' does not exist");
    if (fs::is_directory(p))
        throw FileError("cannot write '" + finalPath_ + "': it is a directory");
    removeAbandonedTemporaries(dir.string());
    tempPath_ = temporaryBeside(finalPath_, "tmp");
    // Created now, so that an unwritable folder is reported as such rather than as whatever
    // the image or VDB encoder says when it cannot open its file.
    const int fd = ::open(tempPath_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) {
        const int error = errno;
        const std::string folder = dir.empty() ? std::string(".") : dir.string();
        throw FileError("cannot write '" + finalPath_ + "': cannot create a file in the folder '" +
                        folder + "': " + std::strerror(error) +
                        (error == EACCES || error == EPERM || error == EROFS
                             ? " (write permission is needed there; choose another output folder)"
                             : ""));
    }
    ::close(fd);
}

AtomicOutput::~AtomicOutput() {
    if (!committed_) {
        std::error_code ec;
        fs::remove(tempPath_, ec);
    }
}

void AtomicOutput::commit() {
    std::error_code ec;
    // The temporary exists from the start: a writer that failed silently left it empty.
    const auto bytes = fs::file_size(tempPath_, ec);
    if (ec || bytes == 0) throw FileError("writing '" + finalPath_ + "' produced no data");
    fs::rename(tempPath_, finalPath_, ec);
    if (ec) throw FileError("cannot write '" + finalPath_ + "': " + ec.message());
    committed_ = true;
}

void requireWritableOutput(const std::string& path) { AtomicOutput probe(path); }

void writeTextFile(const std::string& path, const std::string& text) {
    AtomicOutput out(path);
    {
        std::ofstream f(out.tempPath());
        f << text << "\n";
        if (!f) throw FileError("cannot write '" + path + "'");
    }
    out.commit();
}

std::string fileExtension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

}  // namespace lh
