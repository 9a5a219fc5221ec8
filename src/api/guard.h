// api: every public call's errors as raylane::Error: the library's own InputError is one
// already; another std::exception from below (a file that cannot be read, a system error)
// becomes one with the same message. Running out of memory stays std::bad_alloc.
#pragma once

#include <exception>
#include <new>
#include <utility>

#include "core/error.h"

namespace raylane {

template <class Call>
decltype(auto) guarded(Call&& call) {
    try {
        return std::forward<Call>(call)();
    } catch (const Error&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(e.what());
    }
}

/// Throws Error "name: value is outside lo .. hi" unless lo <= value <= hi.
void check_range(const char* name, long long value, long long lo, long long hi);

}  // namespace raylane
