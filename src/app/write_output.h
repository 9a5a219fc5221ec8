// app: forwards to distribute/write_output.h, where writing a render's films moved (tests/app
// includes it).
#pragma once

#include "distribute/write_output.h"  // IWYU pragma: export
