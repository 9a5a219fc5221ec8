// Tests of a render's region (RenderParams::region) and the parts of a frame (tile_part): a
// pixel has the same bits whatever part of the frame it is rendered in, in both renderers.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "io/load_scene.h"
#include "render/render_packet.h"
#include "render/render_scalar.h"
#include "render/tiles.h"

namespace raylane {
namespace {

/// Whether every pixel of `part` holds the bits of the same pixel of `whole`.
bool same_pixels(const Film& whole, const Film& part, const PixelRect& r, std::string& where) {
    if (part.width != r.width() || part.height != r.height()) {
        where = "film of " + std::to_string(part.width) + "x" + std::to_string(part.height);
        return false;
    }
    for (int y = r.y0; y < r.y1; ++y) {
        for (int x = r.x0; x < r.x1; ++x) {
            if (std::memcmp(&whole.at(x, y), &part.at(x - r.x0, y - r.y0), sizeof(vec3)) != 0) {
                where = "pixel " + std::to_string(x) + ", " + std::to_string(y);
                return false;
            }
        }
    }
    return true;
}

/// Odd rectangles (one pixel, one row, one column, across tiles, the whole frame) of the
/// built-in scene and of the glass bunny (secondary rays in the wavefront): the same bits as the
/// whole frame, in both renderers.
TEST(Region, EveryRectangleHasTheWholeFramesPixels) {
    for (const char* name : {"builtin", "fig10_glass_bunny"}) {
        SceneData scene = load_scene(std::string(RAYLANE_SOURCE_DIR) + "/scenes/" + name + ".json");
        scene.camera.width = 45;
        scene.camera.height = 37;
        const Accel accel = build_accel(scene, BuildParams{});
        const PixelRect rects[] = {{0, 0, 1, 1},     {17, 20, 18, 21}, {44, 36, 45, 37},
                                   {0, 13, 45, 14},  {31, 0, 32, 37},  {3, 5, 40, 31},
                                   {16, 16, 32, 32}, {0, 0, 45, 37}};
        for (bool scalar : {false, true}) {
            RenderParams p;
            p.spp = 3;
            const RenderResult whole =
                scalar ? render_scalar(scene, accel, p) : render_packet(scene, accel, p);
            double sum = 0;  // a black frame would prove nothing
            for (const vec3& c : whole.film.pixels) sum += c.x + c.y + c.z;
            EXPECT_GT(sum, 0.01 * double(whole.film.pixels.size())) << name;
            for (const PixelRect& r : rects) {
                p.region = r;
                const RenderResult part =
                    scalar ? render_scalar(scene, accel, p) : render_packet(scene, accel, p);
                std::string where;
                EXPECT_TRUE(same_pixels(whole.film, part.film, r, where))
                    << name << (scalar ? " scalar" : " packet") << ", region " << r.x0 << " "
                    << r.y0 << " " << r.x1 << " " << r.y1 << ": " << where;
                EXPECT_EQ(part.stats.primary_rays, uint64_t(r.width() * r.height() * 3));
            }
        }
    }
}

TEST(Region, OutsideTheFrameIsRefused) {
    SceneData scene = make_builtin_scene();
    scene.camera.width = 20;
    scene.camera.height = 10;
    const Accel accel = build_accel(scene, BuildParams{});
    RenderParams p;
    p.region = {0, 0, 21, 10};
    EXPECT_THROW(render_packet(scene, accel, p), std::invalid_argument);
    p.region = {-1, 0, 5, 5};
    EXPECT_THROW(render_scalar(scene, accel, p), std::invalid_argument);
}

TEST(Region, MakeTilesTakesTheGridTilesThatMeetTheRegion) {
    const std::vector<Tile> all = make_tiles(50, 40, 16);
    ASSERT_EQ(all.size(), 12u);  // 4 columns (the last 2 wide) by 3 rows (the last 8 high)
    const std::vector<Tile> some = make_tiles(50, 40, 16, {15, 16, 17, 17});
    ASSERT_EQ(some.size(), 2u);
    EXPECT_EQ(some[0], (Tile{0, 16, 16, 32}));
    EXPECT_EQ(some[1], (Tile{16, 16, 32, 32}));
    const std::vector<Tile> corner = make_tiles(50, 40, 16, {49, 39, 50, 40});
    ASSERT_EQ(corner.size(), 1u);
    EXPECT_EQ(corner[0], (Tile{48, 32, 50, 40}));
}

/// Parts I of N for N = 1, 2, 7 and 16 of a frame of 10 x 8 tiles (the last row and column
/// narrower): on the grid, disjoint, and together the whole frame.
TEST(TilePart, PartsCutTheGridWithoutGapOrOverlap) {
    const int width = 150, height = 120, tile = 16;
    for (int n : {1, 2, 7, 16, 80}) {
        std::vector<int> owner(size_t(width * height), -1);
        for (int i = 0; i < n; ++i) {
            const PixelRect r = tile_part(width, height, tile, i, n);
            ASSERT_FALSE(r.empty()) << i << "/" << n;
            EXPECT_EQ(r.x0 % tile, 0) << i << "/" << n;
            EXPECT_EQ(r.y0 % tile, 0) << i << "/" << n;
            EXPECT_TRUE(r.x1 % tile == 0 || r.x1 == width) << i << "/" << n;
            EXPECT_TRUE(r.y1 % tile == 0 || r.y1 == height) << i << "/" << n;
            for (int y = r.y0; y < r.y1; ++y) {
                for (int x = r.x0; x < r.x1; ++x) {
                    int& o = owner[size_t(y * width + x)];
                    EXPECT_EQ(o, -1) << "pixel " << x << ", " << y << " in parts " << o << " and "
                                     << i << " of " << n;
                    o = i;
                }
            }
        }
        for (size_t p = 0; p < owner.size(); ++p)
            ASSERT_NE(owner[p], -1) << "pixel " << p % width << ", " << p / width << " of " << n;
    }
}

TEST(TilePart, MorePartsThanTilesAreRefused) {
    EXPECT_THROW(tile_part(150, 120, 16, 0, 81), std::invalid_argument);
    EXPECT_THROW(tile_part(150, 120, 16, 3, 3), std::invalid_argument);
    EXPECT_THROW(tile_part(150, 120, 16, 0, 0), std::invalid_argument);
}

}  // namespace
}  // namespace raylane
