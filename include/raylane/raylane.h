// raylane/raylane.h: the whole Raylane library: scenes rendered to float images, ray queries
// against triangle meshes, the instruction sets, errors. docs/library.md shows each call.
#pragma once

#include "raylane/error.h"
#include "raylane/instruction_sets.h"
#include "raylane/mesh.h"
#include "raylane/scene.h"
#include "raylane/version.h"
