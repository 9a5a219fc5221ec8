// api: the argument checks every public call shares (api/guard.h).
#include "api/guard.h"

#include <string>

namespace raylane {

void check_range(const char* name, long long value, long long lo, long long hi) {
    if (value >= lo && value <= hi) return;
    std::string m = name;
    m.append(": ").append(std::to_string(value)).append(" is outside ");
    throw Error(m.append(std::to_string(lo)).append(" .. ").append(std::to_string(hi)));
}

}  // namespace raylane
