// Test support: the message of the InputError a reader throws, and where the shared models are.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "core/error.h"

namespace raylane::test {

/// ../shared/models, beside the repository.
inline const std::string models_dir = RAYLANE_SHARED_DIR "/models";

/// What load() throws as InputError; a test failure and "" when it throws nothing.
template <class F>
std::string input_error_of(F load) {
    try {
        load();
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no InputError thrown";
    return "";
}

}  // namespace raylane::test
