// io: the one place stb_image (Sean Barrett, public domain; Debian's libstb-dev) is configured.
// The decoder itself is compiled in io/stb_image.cpp, with signed overflow defined (see there);
// io/load_image.cpp includes this header for the declarations and the allocation budget.
#pragma once

#include <cstddef>

namespace raylane {

/// The largest single allocation stb_image may make on this thread (bytes): a failed allocation
/// makes stb return an error. Small outside a decode (the header probes need a few KiB);
/// io/load_image.cpp sets it from the image size around each decode (AllocationBudget).
extern thread_local size_t stb_allocation_limit;

void* stb_malloc(size_t bytes);
void* stb_realloc(void* p, size_t bytes);
void stb_free(void* p);

}  // namespace raylane

// Only the three formats Raylane reads: TGA has no signature and would accept almost any bytes,
// and every decoder left out is attack surface gone.
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_ONLY_HDR
#define STBI_NO_STDIO
#define STBI_FAILURE_USERMSG
#define STBI_MALLOC(bytes) raylane::stb_malloc(bytes)
#define STBI_REALLOC(p, bytes) raylane::stb_realloc(p, bytes)
#define STBI_FREE(p) raylane::stb_free(p)
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#if !defined(__clang__)
#pragma GCC diagnostic ignored "-Wduplicated-branches"
#endif
#endif
#include <stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
