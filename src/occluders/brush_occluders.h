// SPDX-License-Identifier: MIT
// A level's brushes as occluders: the skins of skin-source=brushes
// (occluders/skin_occluders.h). Leone et al., section 4, take occluders
// made by hand as the best; a level's designer made its solids as
// brushes. Derived from the level's opaque solid brushes (scene/level.h,
// Level::opaque_solids, in Quake's units, where the rules below
// measure their slivers) and the scene's opaque triangles, by the
// strategies that ask for them, not by the loader.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "geometry/aabb.h"
#include "scene/scene.h"

namespace occu {

struct LevelBrushOccluders {
    // Brushes are the designer's own solids, which Leone et al. (section
    // 4) take as the best occluders when made by hand. A brush hides what
    // lies behind it from an eye only where every ray from the eye that
    // enters it first meets a drawn opaque face, and a ray enters a convex
    // brush through a side whose outer half-space holds the eye. That a
    // side's shader is drawn is not enough, nor that it lies against
    // another solid: designers give the sides no player is meant to see
    // the nodraw shader common/caulk (SURF_NODRAW, 0x80), and such sides
    // face open space too (behind a level's outer walls, where random eyes
    // stand; under patches and models); the compiler also drops the faces
    // of drawn sides that face the void outside the level. So a side
    // counts as drawn where the level's own opaque drawn triangles, in the
    // side's plane and facing out of the brush, cover all of it.
    struct OpaqueBrush {
        std::vector<glm::vec4> planes;   // occu's: inside where dot(normal, p) <= w
        std::vector<bool> drawn;         // per side: drawn all over
        // Whether every side whose outer half-space holds `eye` is drawn
        // all over: a ray from there that enters the brush meets a drawn
        // face first.
        bool closed_from(const glm::vec3 &eye) const
        {
            for (std::size_t k = 0; k < planes.size(); ++k)
                if (!drawn[k] && glm::dot(glm::vec3(planes[k]), eye) > planes[k].w)
                    return false;
            return true;
        }
    };
    // One per opaque solid brush, in the order of Level::opaque_solids.
    std::vector<OpaqueBrush> opaque_brushes;
    struct BoxBrush {
        Aabb bounds;   // one unit inside the brush's sides, occu's coordinates
        // Per side, 2 * axis + (1: the side at bounds.max), occu's axes: a
        // side is closed when drawn all over, or when the opaque brushes
        // `against` (into opaque_brushes) lie just outside the rest of it;
        // a ray entering there comes through one of those, so they must
        // each be closed_from the eye.
        struct Side {
            bool closed = false;
            std::vector<std::int32_t> against;
        };
        std::array<Side, 6> sides;
        std::int32_t brush = 0;    // into opaque_brushes
        std::int32_t number = 0;   // in the brushes lump
        // Whether the box hides what lies behind it from `eye` (outside
        // every opaque brush): every side whose outer half-space holds the
        // eye is closed, with the brushes against it closed from the eye.
        bool hides_from(const glm::vec3 &eye, const std::vector<OpaqueBrush> &brushes) const
        {
            for (int a = 0; a < 3; ++a)
                for (int high = 0; high < 2; ++high) {
                    if (high ? !(eye[a] > bounds.max[a]) : !(eye[a] < bounds.min[a]))
                        continue;
                    const Side &side = sides[std::size_t(2 * a + high)];
                    if (!side.closed)
                        return false;
                    for (std::int32_t o : side.against)
                        if (!brushes[std::size_t(o)].closed_from(eye))
                            return false;
                }
            return true;
        }
    };
    // Only those with at least one side closed.
    std::vector<BoxBrush> box_brushes;
};

// The box brushes of a level (Scene::level) and what they hide from which
// eyes, from its opaque solid brushes and the scene's opaque triangles.
// Clips every brush side against the triangles in its plane: about 0.1 to
// 0.3 s a level, so made only for the strategies that ask
// (skin-source=brushes). Throws std::runtime_error on a scene that is no
// level.
LevelBrushOccluders level_brush_occluders(const Scene &scene);

}  // namespace occu
