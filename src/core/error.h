// core: the one error type for bad input, the public raylane::Error (raylane/error.h). The
// message is already the single line the user sees: "file:line: reason" (or "file: byte N:
// reason", "file: $.json.path: reason").
#pragma once

#include "raylane/error.h"

namespace raylane {

/// What every loader throws on malformed input; `raylane` prints what() and exits with code 2.
using InputError = Error;

}  // namespace raylane
