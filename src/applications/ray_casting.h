// SPDX-License-Identifier: MIT
// Ray casting accelerated by verbose occlusion lists: Bartz, Meissner and
// Huettner, "Extending Graphics Hardware For Occlusion Queries In OpenGL"
// (1998), section 5, "Support for Ray Casting".
//
// The paper: "One of the results of the GL_BRIEF_OCCLUSION and
// GL_VERBOSE_OCCLUSION modes is a list of not occluded pixels of the tested
// subdivision entity. [...] this information can be used to accelerate ray
// casting in a mixed volume graphics and polygon model. [...] we render the
// subdivision entities in an occlusion mode. All computed non-occlusion
// hits for this entity mark pixels which are not occluded. Consequently,
// these pixels are image plane parts to cast rays through [...] all pixels
// without an non-occlusion hit are not visible and therefore, rays casted
// through those pixels of the image plane have no contribution."
//
// How occu reads it (volume/density_volume.h has the volume, its bricks and
// the ray marcher):
//
//  * The polygons are drawn first, as a frame normally is; their depth
//    buffer is what the bricks are tested against, and where each ray
//    stops.
//  * The subdivision entities are the volume's non-empty bricks (a brick
//    whose density is zero everywhere adds nothing to any ray, so it needs
//    no test). They are drawn, front faces only, in one
//    GL_VERBOSE_OCCLUSION_MESAX pass: a pixel is listed when a brick's front
//    face there is nearer than the polygons. A ray gains something only
//    from a sample of density > 0 in front of the polygons, and such a
//    sample lies in a non-empty brick whose front face the ray crosses
//    before it, so every pixel whose ray could gain anything is listed; the
//    caster casts rays through the listed pixels alone, and the image is
//    the one casting a ray through every pixel gives, pixel for pixel (the
//    tests check it on both drivers). Which brick a pixel came from does
//    not matter here, only the union, so the pass's tiles are a grid over
//    the viewport that keeps each list short, not one tile per brick (the
//    tiles of one pass cannot be tied to overlapping primitives).
//  * Rasterization and the ray agree only up to float arithmetic: the GL
//    sees a brick at pixel centres through float matrices and a 24-bit
//    depth buffer, the ray is double precision. So each brick is drawn
//    grown by two pixel footprints at its farthest corner (a margin far
//    above float and depth-buffer error; derived in the .cpp), which lists
//    a rim of extra pixels and never drops one.
//  * Bricks outside the frustum or wholly in front of the near plane hold
//    no sample of any pixel's ray (rays start on the near plane) and are
//    not drawn. A brick in the frustum that (grown) crosses the near plane
//    or holds the eye has no unclipped front faces to test with: the pass
//    cannot speak for it, and the frame casts every pixel
//    (stats.whole_frame).
//  * A tile whose list overflows (its room is list_layers pairs per pixel
//    of the tile: a pixel is listed once per brick it sees) falls back to
//    the rectangle of its record's extents, which bound every non-occluded
//    fragment whether listed or not.
#pragma once

#include <cstdint>
#include <vector>

#include "camera/camera.h"
#include "gl/occlusion_unit.h"
#include "render/scene_renderer.h"
#include "spatial/hierarchy.h"
#include "volume/density_volume.h"

namespace occu {

struct OcclusionRayCastingSettings {
    int brick_cells = 8;     // the subdivision entities' size: cells per brick edge (the knob)
    int list_layers = 4;     // verbose list room per tile, in pairs per pixel of the tile
    int tile_pixels = 64;    // the pass's tiles: squares of this many pixels (grown to fit the unit's tiles)
};

struct OcclusionRayCastingStats {
    std::size_t bricks = 0;            // non-empty bricks
    std::size_t bricks_drawn = 0;      // of them, in the pass: in the frustum, beyond the near plane
    std::size_t listed_pixels = 0;     // pixels to cast rays through
    std::size_t tiles = 0, tiles_overflowed = 0;
    bool whole_frame = false;          // a brick crosses the near plane: every pixel is cast
    double pass_ms = 0.0;              // drawing the bricks and ending the pass (its wait included)
    double mask_ms = 0.0;              // turning the records into the pixel mask
};

class OcclusionRayCasting {
public:
    // Needs a current context with GL_MESAX_occlusion_unit (throws
    // std::runtime_error otherwise); throws std::invalid_argument for
    // settings below 1.
    OcclusionRayCasting(const DensityVolume &volume, const OcclusionRayCastingSettings &settings);

    // The pixels to cast rays through (1) and the others (0), row by row
    // from the bottom, for the frame of `camera` whose depth buffer is in
    // the framebuffer bound now, viewport (0, 0, width, height). The
    // caller's state and matrices are as they were.
    const std::vector<std::uint8_t> &pixels_to_cast(const Camera &camera, int width, int height);

    const OcclusionRayCastingStats &stats() const { return stats_; }
    const OcclusionRayCastingSettings &settings() const { return settings_; }

private:
    gl::OcclusionUnit unit_;
    PFNGLBINDBUFFERPROC BindBuffer_ = nullptr;
    OcclusionRayCastingSettings settings_;
    std::vector<Aabb> bricks_;   // the non-empty ones
    std::vector<std::uint8_t> mask_;
    OcclusionRayCastingStats stats_;
};

// The polygon part of the mixed scene, drawn as a frame is: clears colour
// (to `sky`) and depth, then draws every leaf in the frustum of `camera`
// with back faces culled and the depth test on (GL_LESS). Leaves the
// camera loaded.
void draw_polygons(const SceneRenderer &renderer, const Hierarchy &hierarchy, const Camera &camera,
                   const glm::vec3 &sky = {0.55f, 0.7f, 0.9f});

// The depth buffer of the framebuffer bound now, viewport (0, 0, width,
// height), as window z in [0, 1], row by row from the bottom.
std::vector<double> read_window_depth(int width, int height);

struct CompositeStats {
    std::size_t rays = 0;            // rays cast
    std::size_t contributing = 0;    // of them, rays whose volume samples added something
    double ms = 0.0;
};

// Composites the volume over a frame: `frame_rgba` (RGBA8, bottom row
// first) and its `depth` (read_window_depth); casts a ray through every
// pixel where `mask` is 1, or through every pixel if mask is null, and
// copies the frame's pixel elsewhere. Writes `out_rgba` (alpha 255) and,
// if `contributes` is not null, 1 where a ray gained something.
CompositeStats composite_volume(const VolumeRayCaster &caster, int width, int height, const std::uint8_t *frame_rgba,
                                const std::vector<double> &depth, const std::uint8_t *mask, std::uint8_t *out_rgba,
                                std::vector<std::uint8_t> *contributes = nullptr);

}  // namespace occu
