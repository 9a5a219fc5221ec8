// raylane/error.h: the one exception type of the Raylane library.
#pragma once

#include <stdexcept>
#include <string>

namespace raylane {

/// Bad input of any kind: a scene, model or image file that cannot be read, an argument out of
/// range, arrays that do not fit. what() is the one line the `raylane` command prints, e.g.
/// "scenes/room.json:12: unknown material 'glas'" or "spp: -1 is outside 0 .. 1048576".
class Error : public std::runtime_error {
  public:
    explicit Error(const std::string& message);
    ~Error() override;
};

}  // namespace raylane
