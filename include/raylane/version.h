// raylane/version.h: which Raylane a program runs against.
#pragma once

namespace raylane {

/// The library's version, "MAJOR.MINOR.PATCH", as `raylane --version` prints it.
const char* version();

}  // namespace raylane
