// distribute: what every frame and part of `raylane render` shares, for the plain and the MPI
// render.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "accel/bvh.h"
#include "distribute/part.h"
#include "distribute/write_output.h"
#include "render/render_params.h"
#include "scene/scene.h"

namespace raylane {

struct RenderJob {
    SceneData scene;  ///< its camera is the frame's while a frame renders (render_part)
    Camera still;     ///< the scene's own camera, which the animation moves
    Accel accel;
    RenderParams params;    ///< the user's seed; no region; params.aov is aovs[0]
    std::vector<Aov> aovs;  ///< what each frame renders: one AOV, or all four (--aov all)
    bool scalar = false;
    bool exr_float = false;  ///< EXR channels as 32-bit floats (parts always are)
    bool strict = false;     ///< --strict: exit with 3 when a sample was NaN or infinite
    bool quiet = false;      ///< -q: no progress, no summary; warnings and errors only
    PartInfo info;           ///< the scene's hash and the settings, for EXR headers
    std::string output;      ///< a file, or a pattern with a frame number (frame_output)
    int first_frame = 0, last_frame = 0;
    PixelRect region;            ///< the part of each frame to render (the whole frame by default)
    std::string bvh = "median";  ///< the --bvh build, for the summary
    double load_ms = 0.0, build_ms = 0.0;  ///< for the summary
    std::string progress_label;            ///< "frame N" while frame N renders
};

/// A frame's (or a part's) films, one per AOV of the job, and the counts of the first.
struct PartResult {
    std::vector<AovFilm> films;
    RenderStats stats;
};

/// Renders `region` of frame `frame`, every AOV of the job: the frame's camera and seed
/// (frame_seed), the job's renderer. The films are the region's size.
PartResult render_part(RenderJob& job, int frame, const PixelRect& region);

/// The file name of frame `frame`: the pattern's one printf conversion (%d, %4d or %04d)
/// replaced by the frame number, %% by %. A pattern without one is the name of every frame.
std::string frame_output(const std::string& pattern, int frame);

/// Whether a name holds a frame number conversion; throws InputError for a '%' that is not one
/// (or a second one).
bool has_frame_number(const std::string& pattern);

/// Writes a frame's films to its file (write_render_output; a part of a frame to an .exr is a
/// part file, write_part) and prints what a frame says (one line per frame when there are
/// several). The films are taken by value: pass an rvalue to map them in place.
void write_frame(const RenderJob& job, int frame, std::vector<AovFilm> films,
                 const RenderStats& stats);

/// The exit code of a job whose frames counted `total`: 3, with a line on stderr, under --strict
/// when a sample was NaN or infinite, else 0.
int strict_exit_code(const RenderJob& job, const RenderStats& total);

/// The frames A..B of --frames ("A..B", "A", or "all" of the scene's animation), checked against
/// the animation's frames; a range A..B whose end is past the last frame stops there.
void parse_frames(const std::string& text, int frame_count, int& first, int& last);

/// The part of the frame --crop or --tile names (empty when neither is given): a crop is checked
/// inside the frame; part I of N cuts the renderer's tile grid (tile_part in render/tiles.h).
PixelRect parse_region(const std::vector<int>& crop, const std::string& tile, int width,
                       int height);

/// Prints what is being rendered (before the progress line): scene, resolution, part, frames,
/// renderer, and ranks when more than one.
void print_header(const RenderJob& job, int ranks);

/// True when this process is one of several started by an MPI launcher (mpirun sets
/// OMPI_COMM_WORLD_SIZE; MPICH's and Slurm's launchers PMI_SIZE).
bool launched_by_mpi();
/// This process's rank from the launcher's environment (0 when not launched by one): decides
/// which process prints an error that every process meets.
int rank_from_environment();

#ifdef RAYLANE_MPI
/// Renders a job's frames over the ranks of MPI_COMM_WORLD (distribute/render_mpi.cpp): every rank
/// makes the job with `make_job` (loads the scene; an InputError on any rank stops every rank
/// with one line and exit code 2) and builds the BVH; rows of tiles (or pieces of them) go out
/// on demand; rank 0 renders too, gathers the pixels and writes every frame. Returns the exit
/// code.
int render_over_mpi(const std::function<RenderJob()>& make_job);
#endif

}  // namespace raylane
