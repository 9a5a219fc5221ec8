// core: the public raylane::Error's constructor and destructor, defined once here so that its
// type information lives in the library (a program catches the library's Error as its own).
#include "core/error.h"

namespace raylane {

Error::Error(const std::string& message) : std::runtime_error(message) {}
Error::~Error() = default;

}  // namespace raylane
