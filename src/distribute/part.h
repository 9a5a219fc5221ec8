// distribute: parts of a frame, the EXR files `render` writes for a region and `assemble` joins.
// A part is a 32-bit float EXR whose display window is the whole frame and whose data window is
// the region it holds; its header names the scene (raylane:scene) and the render settings the
// parts of one frame share (raylane:settings).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "distribute/write_output.h"
#include "image/exr.h"
#include "render/render_params.h"
#include "scene/scene.h"

namespace raylane {

/// What the parts of one frame share, besides the frame's size.
struct PartInfo {
    std::string scene;  ///< scene_hash (scene_hash.h)
    /// Settings that change pixels, as (name, value), in order: "aov" (aov_name, or "all" for
    /// the four layers of --aov all) and "tonemap" (srgb, report) first, then e.g. spp, seed,
    /// path, bvh, light_samples, glossy_samples, frame. Names are identifiers; values hold no ';'.
    std::vector<std::pair<std::string, std::string>> settings;
};

/// The settings of a render: aov, tonemap (the scene's), spp, seed, path ("packet", "scalar"),
/// bvh ("median", "sah"), light_samples and glossy_samples, and the scene's hash.
PartInfo make_part_info(const SceneData& scene, const RenderParams& params, const std::string& path,
                        const std::string& bvh);

/// The value of a setting, or "" when the info has none.
std::string part_setting(const PartInfo& info, const std::string& name);
/// Sets a setting, replacing its value or adding it at the end.
void set_part_setting(PartInfo& info, const std::string& name, const std::string& value);

/// The EXR attributes of a part or of a whole frame: raylane:scene (the hash) and
/// raylane:settings ("aov=color; tonemap=srgb; spp=16; ...").
std::vector<std::pair<std::string, std::string>> frame_attributes(const PartInfo& info);

/// Writes the part [x0, x0 + w) x [y0, y0 + h) of a frame_width x frame_height frame, where
/// w x h is the size of the films (raw render results, one per AOV, as write_render_output
/// takes them), as a 32-bit float EXR with frame_attributes(info). Throws std::runtime_error
/// when it cannot write, std::invalid_argument when the part is not inside the frame.
void write_part(const std::string& path, std::vector<AovFilm> films, int x0, int y0,
                int frame_width, int frame_height, const PartInfo& info);
/// write_part of one film, the AOV part_setting(info, "aov") names.
void write_part(const std::string& path, const Film& part_film, int x0, int y0, int frame_width,
                int frame_height, const PartInfo& info);

/// A part as read back.
struct Part {
    std::string path;
    ExrImage image;
    PartInfo info;
};

/// Reads a part. Throws InputError ("path: reason") when the file is missing, truncated or not
/// an EXR, when it is not a Raylane part (no raylane:scene or raylane:settings), or holds 16-bit
/// halves.
Part read_part(const std::string& path);

/// A frame joined from parts: its films (one per layer of the parts, raw) and what they share.
struct JoinedFrame {
    std::vector<AovFilm> films;
    PartInfo info;
    Tonemap tonemap = Tonemap::srgb;
};

/// Joins parts into their frame. Throws InputError with one line naming the file (or files) and
/// the reason when the parts come from different frame sizes, scenes or settings (naming the
/// setting that differs), hold different channels, overlap (naming the pixels both hold), or
/// leave a gap (naming pixels no part holds).
JoinedFrame join_parts(std::vector<Part> parts);

}  // namespace raylane
