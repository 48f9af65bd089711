// SPDX-License-Identifier: MIT
// Cull maps: Wonka, Wimmer and Schmalstieg, "Visibility Preprocessing with
// Occluder Fusion for Urban Walkthroughs" (2000), sections 1.3 ("Cull
// Maps", figures 3 and 4), 2.2 ("Hardware rasterization of shrunk
// occluders") and 5 ("Rendering and Merging Occluder Shadows").
//
// A cull map is a depth buffer seen from straight above: pixel (i, j) is
// the ground square of k x k metres at region.min + (i, j) k (x to the
// right, z up the image), and its depth encodes a height, the umbra's:
// everything in that square below it is hidden from the view cell. Window
// depth d stands for height top - d (top - bottom), so the depth test
// GL_LESS keeps the higher shadow ("the z-buffer automatically stores the
// z-value which provides the best occlusion"); heights beyond [bottom,
// top] are clamped (GL_DEPTH_CLAMP), not clipped.
//
// Occluder shadows: for a sample point P and a prism occluder of height H
// (shrunk, footprint_shrinking.h), each edge (a, b) of its
// footprint casts the quadrilateral of the plane through P and the edge's
// top (a, H)-(b, H), from the edge away from P to beyond the map: a point
// below that plane, seen from P across the edge, is behind the wall. The
// union over occluders is the depth test; the intersection over a view
// cell's sample points is section 5's two passes with the stencil buffer
// (add_sample_point). The paper's conservative rasterization comes from the
// shrinking: with epsilon >= k sqrt(2) / 2 the shadows need no correction
// for sampling at pixel centres (section 2.2; the caller keeps the coupling).
//
// Object tests, two ways (both decide "visible" for an axis-aligned box
// when its top is above the umbra at some pixel of its footprint, the
// pixels whose squares meet the box's x-z extent):
//  * the paper's (section 5, "the cull map is copied to main memory"):
//    read the depth buffer back and compare on the CPU;
//  * the Occlusion Unit's (Bartz et al., section 3): draw each box's top,
//    a quad at its maximum height exactly over its footprint's pixels, in
//    GL_BRIEF_OCCLUSION_MESAX passes with one tile per box (boxes whose
//    pixels overlap go to different passes: a tile counts every fragment
//    in it), NOHC > 0 meaning visible; nothing is read but the records.
// Both compare the same 24-bit depths with the same rule, so they agree
// box for box; a box whose top quantizes to a map value within one step
// could go either way in float, and tests report such ties apart.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "geometry/aabb.h"
#include "geometry/pixel_rect.h"
#include "gl/framebuffer.h"
#include "gl/occlusion_unit.h"
#include "scene/scene.h"

namespace occu {

struct CullMapRegion {
    glm::dvec2 min{0.0};   // ground (x, z) of pixel (0, 0)'s lower corner
    int width = 1, height = 1;
    double pixel = 1.0;    // metres per pixel, k

    glm::dvec2 max() const { return min + pixel * glm::dvec2(width, height); }
    // The pixels whose squares meet [lo, hi] (x, z), clamped to the map;
    // empty when none do.
    PixelRect pixels_of(const glm::dvec2 &lo, const glm::dvec2 &hi) const;
};

class CullMap {
public:
    // Needs a current context with framebuffer objects and depth clamping.
    // Heights are encoded within [bottom, top]. Throws std::invalid_argument
    // unless bottom < top, both finite.
    CullMap(double bottom, double top);

    // Starts a map over `region` (at most 16384 pixels a side): no umbra.
    void begin(const CullMapRegion &region);
    // Fuses the shadows of `occluders` from `p` into the map: their union,
    // intersected with the map so far unless p is the first sample point.
    void add_sample_point(const glm::dvec3 &p, const std::vector<const PrismOccluder *> &occluders);

    const CullMapRegion &region() const { return region_; }
    std::size_t sample_points() const { return samples_; }

    // The map as 24-bit depth values, row by row from the bottom (read back).
    std::vector<std::uint32_t> read_depths() const;
    // A height's depth value, as the GL stores a fragment at that height.
    std::uint32_t depth_of(double height) const;
    double height_of(std::uint32_t depth) const;

    // The map's outermost ring of pixels (section 6's cull map horizon), read
    // alone: 2 (width + height) values, not the map.
    class Horizon {
    public:
        // Depth at border pixel (x, y) (x in {0, width - 1} or y in {0, height - 1}).
        std::uint32_t at(int x, int y) const;

    private:
        friend class CullMap;
        int width_ = 0, height_ = 0;
        std::vector<std::uint32_t> bottom_, top_, left_, right_;
    };
    Horizon read_horizon() const;
    static Horizon horizon_of(const CullMapRegion &region, const std::vector<std::uint32_t> &depths);

    // The read-back test: `depths` from read_depths(). A box whose pixels
    // all lie outside the map is neither (std::nullopt).
    std::optional<bool> visible_by_readback(const Aabb &box, const std::vector<std::uint32_t> &depths) const;
    // The Occlusion Unit test of every box (needs GL_MESAX_occlusion_unit);
    // boxes outside the map are std::nullopt. `passes` counts the passes run.
    std::vector<std::optional<bool>> visible_by_unit(const gl::OcclusionUnit &unit, const std::vector<Aabb> &boxes,
                                                     std::size_t *passes = nullptr) const;

private:
    // The shadow quadrilaterals of `occluders` from `p`, as glVertexPointer's
    // (x, z, depth) triples: made once per sample point, drawn by each pass.
    std::vector<double> shadow_quads(const glm::dvec3 &p, const std::vector<const PrismOccluder *> &occluders) const;
    PixelRect box_pixels(const Aabb &box) const;

    double bottom_, top_;
    CullMapRegion region_;
    gl::Framebuffer target_;
    std::size_t samples_ = 0;
};

}  // namespace occu
