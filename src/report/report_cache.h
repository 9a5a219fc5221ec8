// report: the converged references (error-vs-time.md, "What it does"): rendered in chunks by
// either path, and kept on disk under a key of everything they depend on.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "accel/bvh.h"
#include "image/film.h"
#include "render/render_params.h"
#include "scene/scene.h"

namespace raylane {

/// The renderer of a reference or of a sweep's point.
enum class RenderPath : uint8_t { packet, scalar };
const char* path_name(RenderPath path);
/// render_packet or render_scalar.
RenderResult render_with(RenderPath path, const SceneData& scene, const Accel& accel,
                         const RenderParams& params);

/// Seeds of converged references start here (chunk k uses reference_seed + k); sweeps use
/// seeds from 1 up, so the two never share samples.
inline constexpr uint32_t reference_seed = 0x52454600u;

struct ReferenceParams {
    int spp = 6400;      ///< total samples per pixel (>= 4)
    int chunk_spp = 64;  ///< samples per render call (>= 2: one sample is the pixel centre)
    int threads = 0;
    uint32_t seed = reference_seed;
    RenderPath path = RenderPath::packet;
};

struct Reference {
    Film film;
    std::string kind;       ///< "converged" or "analytic: <case>"
    int spp = 0;            ///< 0 for analytic references
    double variance = 0.0;  ///< Var(ref) per value, from the halves A and B; 0 when analytic
    uint64_t nan_samples = 0;
    double seconds = 0.0;  ///< time to render (or evaluate) it
};

/// Called after each chunk: (chunks done, chunks in all).
using ChunkProgress = std::function<void(int, int)>;

/// A converged reference: chunks of chunk_spp samples with seeds seed, seed + 1, ...; even
/// chunks form half A, odd chunks half B; the reference is their sample-weighted mean in double,
/// Var(ref) = MSE(A, B) / (N (1/n_A + 1/n_B)) (= MSE(A, B) / 4 for equal halves).
Reference render_converged_reference(const SceneData& scene, const Accel& accel,
                                     const ReferenceParams& params,
                                     const ChunkProgress& progress = {});

/// Hex key of a converged reference on disk: FNV-1a 64 of the scene file's bytes, the path,
/// size and modification time of every file the scene names (any string value that is an
/// existing file in the model search path), width, height, reference spp, chunk size, seed and
/// renderer. Throws InputError when the scene file cannot be read.
std::string reference_cache_key(const std::string& scene_path, int width, int height,
                                const ReferenceParams& params);

/// Writes the reference as PFM (image/pfm.h) plus a "<path>.txt" sidecar (spp, Var(ref), NaN
/// samples, seconds, `build`). Throws std::runtime_error when the files cannot be written.
void save_reference(const std::string& pfm_path, const Reference& ref, const std::string& build);
/// Reads what save_reference wrote; nullopt when either file is missing, malformed or not
/// width x height (a cache miss, never an error). `build` receives the sidecar's build line.
std::optional<Reference> load_reference(const std::string& pfm_path, int width, int height,
                                        std::string* build = nullptr);

}  // namespace raylane
