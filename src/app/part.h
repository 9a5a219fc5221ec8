// app: forwards to distribute/part.h, where the parts of a frame moved (tests/app includes it).
#pragma once

#include "distribute/part.h"  // IWYU pragma: export
