// SPDX-License-Identifier: MIT
#include "applications/ray_casting.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "gl/extensions.h"
#include "gl/state.h"

namespace occu {

namespace {

double ms_since(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// How much a brick is grown before the pass, in metres. The ray of a pixel
// goes through the pixel's centre in double precision; the GL decides the
// same pixel from float vertices (world coordinates rounded to 2^-24 of
// their size, transformed in float), snapped to a sub-pixel grid (1/256
// pixel on llvmpipe) and depth-tested in 24 bits. A brick grown by two
// pixel footprints at its farthest corner has every ray that meets the
// brick proper enter the grown one at least two pixels' width inside its
// silhouette, far beyond the snapping and float error; and its front face
// moves towards the eye by the same two footprints, which at view depth z
// is a window-depth gap of about 4 n tan(fovy/2) / (z H) for a near plane
// n and H pixels (n / z^2 per metre of depth, times the footprint
// 2 z tan(fovy/2) / H): on the city's street views (n = 0.5 m, H = 512,
// z <= 800 m) more than 50 steps of a 24-bit depth buffer. The last term
// covers the float rounding of the box's own coordinates far from the origin.
float brick_margin(const Aabb &brick, const Camera &camera, int width, int height)
{
    double farthest = 0.0, size = 0.0;
    for (int c = 0; c < 8; ++c) {
        const glm::dvec3 p(brick.corner(c));
        farthest = std::max(farthest, glm::length(p - glm::dvec3(camera.position)));
        size = std::max({size, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    }
    const double tan_half = std::tan(glm::radians(double(camera.fovy_degrees)) / 2.0);
    const double footprint =
        std::max(2.0 * farthest * tan_half / double(height), 2.0 * farthest * tan_half * double(camera.aspect) / double(width));
    return float(2.0 * footprint + 1e-5 * (size + 1.0));
}

// Where a brick lies against the near plane: wholly beyond it (view depth
// greater than the plane's at every corner: the eye is outside the box and
// every ray that meets it crosses one of its front faces, unclipped),
// wholly in front of it (no ray samples there: rays start on the near
// plane), or across it.
enum class NearPlaneSide { beyond, in_front, across };
NearPlaneSide near_plane_side(const Aabb &box, const Camera &camera)
{
    const glm::dmat4 view(camera.view());
    int beyond = 0;
    for (int c = 0; c < 8; ++c) {
        const glm::dvec4 v = view * glm::dvec4(glm::dvec3(box.corner(c)), 1.0);
        beyond += -v.z > double(camera.near_plane);
    }
    return beyond == 8 ? NearPlaneSide::beyond : beyond == 0 ? NearPlaneSide::in_front : NearPlaneSide::across;
}

}  // namespace

OcclusionRayCasting::OcclusionRayCasting(const DensityVolume &volume, const OcclusionRayCastingSettings &settings)
    : settings_(settings)
{
    if (settings.brick_cells < 1 || settings.list_layers < 1 || settings.tile_pixels < 1)
        throw std::invalid_argument("ray casting settings: brick cells, list layers and tile pixels must be >= 1");
    BindBuffer_ = reinterpret_cast<PFNGLBINDBUFFERPROC>(gl::get_proc_address("glBindBuffer"));
    if (!BindBuffer_)
        throw std::runtime_error("this GL context lacks glBindBuffer");
    for (const Brick &b : make_bricks(volume, settings.brick_cells))
        if (!b.empty)
            bricks_.push_back(b.box);
}

const std::vector<std::uint8_t> &OcclusionRayCasting::pixels_to_cast(const Camera &camera, int width, int height)
{
    if (width < 1 || height < 1)
        throw std::invalid_argument("a view of " + std::to_string(width) + "x" + std::to_string(height) + " pixels");
    stats_ = {};
    stats_.bricks = bricks_.size();
    mask_.assign(std::size_t(width) * std::size_t(height), 0);

    // Bricks outside the frustum (grown, so a ray that grazes one still
    // finds it inside) or wholly in front of the near plane hold no sample
    // of any pixel's ray.
    const Frustum frustum(camera.view_projection());
    std::vector<Aabb> grown;
    grown.reserve(bricks_.size());
    for (const Aabb &b : bricks_) {
        const float m = brick_margin(b, camera, width, height);
        const Aabb g{b.min - glm::vec3(m), b.max + glm::vec3(m)};
        if (frustum.classify(g) == Frustum::Side::outside)
            continue;
        const NearPlaneSide side = near_plane_side(g, camera);
        if (side == NearPlaneSide::in_front)
            continue;
        if (side == NearPlaneSide::across) {
            stats_.whole_frame = true;
            break;
        }
        grown.push_back(g);
    }
    if (stats_.whole_frame) {
        std::fill(mask_.begin(), mask_.end(), std::uint8_t(1));
        stats_.listed_pixels = mask_.size();
        return mask_;
    }

    // A grid of square tiles over the viewport, grown until the unit has them all.
    int tile = std::max(1, settings_.tile_pixels);
    auto tiles_across = [&](int t) { return ((width + t - 1) / t) * ((height + t - 1) / t); };
    while (tiles_across(tile) > unit_.max_tiles())
        tile *= 2;
    std::vector<PixelRect> tiles;
    std::vector<std::size_t> room;
    for (int y = 0; y < height; y += tile)
        for (int x = 0; x < width; x += tile) {
            const PixelRect t{x, y, std::min(x + tile, width), std::min(y + tile, height)};
            tiles.push_back(t);
            room.push_back(std::size_t(t.width()) * std::size_t(t.height()) * std::size_t(settings_.list_layers));
        }
    stats_.tiles = tiles.size();

    const auto pass_start = std::chrono::steady_clock::now();
    std::vector<gl::OcclusionRecord> records;
    {
        const gl::AttribScope state(GL_ENABLE_BIT | GL_DEPTH_BUFFER_BIT | GL_POLYGON_BIT);
        const gl::MatrixScope matrices;
        gl::load_camera(camera);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        // Front faces only: one fragment per brick a pixel's ray enters.
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
        glFrontFace(GL_CCW);
        // Every brick's faces from one vertex array: one draw, whatever the
        // brick count (immediate mode costs a call per vertex).
        std::vector<float> quads;
        quads.reserve(grown.size() * 6 * 4 * 3);
        for (const Aabb &g : grown)
            for (const auto &face : aabb_faces)
                for (int c : face) {
                    const glm::vec3 p = g.corner(c);
                    quads.insert(quads.end(), {p.x, p.y, p.z});
                }
        glPushClientAttrib(GL_CLIENT_VERTEX_ARRAY_BIT);
        BindBuffer_(GL_ARRAY_BUFFER, 0);   // the vertices are client memory
        glEnableClientState(GL_VERTEX_ARRAY);
        glDisableClientState(GL_COLOR_ARRAY);
        glDisableClientState(GL_NORMAL_ARRAY);
        glVertexPointer(3, GL_FLOAT, 0, quads.data());
        gl::OcclusionPass pass(unit_, gl::OcclusionMode::verbose, tiles, room);
        glDrawArrays(GL_QUADS, 0, GLsizei(quads.size() / 3));
        records = pass.end();
        glPopClientAttrib();
    }
    stats_.bricks_drawn = grown.size();
    stats_.pass_ms = ms_since(pass_start);

    const auto mask_start = std::chrono::steady_clock::now();
    for (const gl::OcclusionRecord &r : records) {
        if (r.nohc == 0)
            continue;
        if (r.overflowed) {
            // The extents bound every non-occluded fragment of the tile, listed or not.
            ++stats_.tiles_overflowed;
            const std::uint32_t x1 = std::min<std::uint32_t>(r.x_max, std::uint32_t(width - 1));
            const std::uint32_t y1 = std::min<std::uint32_t>(r.y_max, std::uint32_t(height - 1));
            for (std::uint32_t y = r.y_min; y <= y1; ++y)
                for (std::uint32_t x = r.x_min; x <= x1; ++x)
                    mask_[std::size_t(y) * std::size_t(width) + x] = 1;
            continue;
        }
        for (const gl::OcclusionRecord::Pixel &p : r.pixels)
            if (p.x < std::uint32_t(width) && p.y < std::uint32_t(height))
                mask_[std::size_t(p.y) * std::size_t(width) + p.x] = 1;
    }
    stats_.listed_pixels = std::size_t(std::count(mask_.begin(), mask_.end(), std::uint8_t(1)));
    stats_.mask_ms = ms_since(mask_start);
    return mask_;
}

void draw_polygons(const SceneRenderer &renderer, const Hierarchy &hierarchy, const Camera &camera, const glm::vec3 &sky)
{
    const gl::AttribScope state(GL_ENABLE_BIT | GL_DEPTH_BUFFER_BIT | GL_POLYGON_BIT | GL_COLOR_BUFFER_BIT);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glClearColor(sky.r, sky.g, sky.b, 1.0f);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl::load_camera(camera);
    for (std::uint32_t leaf : leaves_in_frustum(hierarchy, Frustum(camera.view_projection())))
        renderer.draw_leaf(leaf, LeafPart::all);
}

std::vector<double> read_window_depth(int width, int height)
{
    std::vector<GLuint> raw(std::size_t(width) * std::size_t(height));
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, width, height, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, raw.data());
    std::vector<double> depth(raw.size());
    for (std::size_t i = 0; i < raw.size(); ++i)
        depth[i] = double(raw[i]) / 4294967295.0;
    return depth;
}

CompositeStats composite_volume(const VolumeRayCaster &caster, int width, int height, const std::uint8_t *frame_rgba,
                                const std::vector<double> &depth, const std::uint8_t *mask, std::uint8_t *out_rgba,
                                std::vector<std::uint8_t> *contributes)
{
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    if (depth.size() != pixels)
        throw std::invalid_argument("composite_volume: a depth buffer of " + std::to_string(depth.size()) +
                                    " pixels for a " + std::to_string(width) + "x" + std::to_string(height) + " frame");
    if (contributes)
        contributes->assign(pixels, 0);
    CompositeStats stats;
    const auto start = std::chrono::steady_clock::now();
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
            const std::uint8_t *in = frame_rgba + 4 * i;
            std::uint8_t *out = out_rgba + 4 * i;
            out[0] = in[0], out[1] = in[1], out[2] = in[2], out[3] = 255;
            if (mask && !mask[i])
                continue;
            ++stats.rays;
            const VolumeRayCaster::Result r = caster.cast(x, y, in, depth[i]);
            if (!r.volume_contributes)
                continue;
            ++stats.contributing;
            out[0] = r.rgb[0], out[1] = r.rgb[1], out[2] = r.rgb[2];
            if (contributes)
                (*contributes)[i] = 1;
        }
    stats.ms = ms_since(start);
    return stats;
}

}  // namespace occu
