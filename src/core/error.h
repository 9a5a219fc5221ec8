// core: the one error type for bad input. The message is already the single line the user sees:
// "file:line: reason" (or "file: byte N: reason", "file: $.json.path: reason").
#pragma once

#include <stdexcept>
#include <string>

namespace raylane {

/// Thrown by every loader on malformed input; `raylane` prints what() and exits with code 2.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace raylane
