// Tests of the public API (tests/api): the message of the raylane::Error a call throws.
#pragma once

#include <string>

#include "raylane/error.h"

namespace raylane::test {

/// The message of the raylane::Error `call` throws ("" when it throws none).
template <class Call>
std::string error_of(Call call) {
    try {
        call();
    } catch (const raylane::Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace raylane::test
