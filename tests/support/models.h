// Tests: what a test does when a model it needs (the Stanford bunny or dragon of
// ../shared/models) is missing: it skips, saying where the models come from, or, when
// RAYLANE_REQUIRE_MODELS=1 (CI sets it), it fails: there a missing model is a fault of the set-up.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <string_view>

namespace raylane::test {

/// Whether a missing model fails the test (RAYLANE_REQUIRE_MODELS=1) instead of skipping it.
inline bool models_required() {
    const char* value = std::getenv("RAYLANE_REQUIRE_MODELS");
    return value != nullptr && std::string_view(value) == "1";
}

}  // namespace raylane::test

/// Used as GTEST_SKIP(): `if (!exists(path)) RAYLANE_MODEL_MISSING() << path << " not present";`
#define RAYLANE_MODEL_MISSING()                                                                 \
    return GTEST_MESSAGE_(::raylane::test::models_required()                                    \
                              ? "a model is missing and RAYLANE_REQUIRE_MODELS=1: "             \
                              : "skipped, a model is missing (put ../shared/models beside the " \
                                "checkout or its folder in RAYLANE_MODEL_PATH): ",              \
                          ::raylane::test::models_required()                                    \
                              ? ::testing::TestPartResult::kFatalFailure                        \
                              : ::testing::TestPartResult::kSkip)
