// Typed exceptions thrown by the libraries. Library code never exits; the CLI catches
// once in main, prints one line and returns non-zero (OpenVDB's Exceptions.h model).
#pragma once

#include <stdexcept>
#include <string>

namespace lh {

// Base of every error this project throws on purpose.
struct Error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// A file is missing, unreadable, corrupt or holds the wrong kind of content.
struct FileError : Error {
    using Error::Error;
};

// A value supplied by the user (option, camera, size, point) is invalid.
struct InputError : Error {
    using Error::Error;
};

// A request would exceed a documented resource bound (memory, image size).
struct ResourceError : Error {
    using Error::Error;
};

}  // namespace lh
