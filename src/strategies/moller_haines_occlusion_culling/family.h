// Möller and Haines, "Occlusion Culling Algorithms" (Real-Time Rendering):
// three of the algorithms the chapter describes, one family each.
//
// hp  (hp_occlusion_test_culler.cpp) "VISUALIZE fx's Hardware
// Implementation": Hewlett-Packard's occlusion test (Bartz et al. 1998,
// section 2 and reference [8]). Before a complex
// object is drawn, the pixels of its bounding box are scan-converted and
// depth tested without being drawn; if none would be visible the object
// is culled. The answer is one flag per box, so every box is its own query
// and the renderer waits for each, front to back; the Occlusion Unit
// (strategies/bartz_occlusion_unit) answers many boxes per pass instead.
//
// Each box is one GL_SAMPLES_PASSED query (ARB_occlusion_query, the HP
// test's successor in core GL: "any samples passed" is the flag), its
// proxy drawn with colour and depth writes off; a batch issues its queries
// and then reads them, so the rasterizer works through the batch before
// the first answer is needed. Boxes without a footprint (they hold the eye
// or cross the near plane) are visible untested.
//
// hzb (hierarchical_z_buffer_culler.cpp) "Hierarchical Z-Buffering and the
// Hierarchical Visibility Algorithm" (Greene, Kass and Miller): a Z-pyramid
// (maps/z_pyramid.h), each level the farthest of 2x2 below, built per frame
// from the occluder skins' CPU depth buffer (raster/depth_rasterizer.h;
// Leone et al.'s occluders) or, source=last-frame, from the depth of the
// leaves the last frame drew, rendered in this frame's view and read back
// (the two-pass scheme of GPU culling). Boxes, front to back, are tested
// from the coarsest level that encloses their footprint in 2x2 texels,
// descending only where a texel is not nearer than the box; with skins, a
// leaf the pyramid keeps is tested again by its box's faces in the skins'
// depth buffer, pixel by pixel, as skins does.
//
// hom (hierarchical_occlusion_map_culler.cpp) "Hierarchical Occlusion Map"
// (Zhang, Manocha, Hudson and Hoff): occluders chosen by size and distance
// from an occluder set (the skins: large, few polygons, tight boxes, the
// criteria the chapter gives), a budget of them per frame that may adapt
// to how much is culled, rendered white on black at the frame's resolution
// on the CPU (raster/depth_rasterizer.h); occlusion map 0 averages blocks
// of map-divisor x map-divisor frame pixels, so its opacity is the covered
// share of each block (maps/hierarchical_occlusion_map.h), its pyramid by
// averaging; the overlap test with opacity thresholds O_{k+1} = (3 + O_k)/4
// (O_0 = 1 - tolerance: the share of a block that may be holes; exact at
// tolerance 0), then the depth test against the depth estimation buffer,
// regions holding their occluders' farthest depth (each occluder polygon's
// farthest vertex, Zhang's estimate).
//
// shadow (shadow_frustum_culler.cpp) "Shadow Culling" (Hudson et al.): a
// few large occluders per frame, chosen by Coorg and Teller's solid-angle
// estimate g = -a (n . v) / (d . d) with last frame's kept unless one
// twice as good appears (occluders/shadow_occluders.h): the faces of the
// occluder skins that face the eye, or (aggregate=on, the default) each
// skin box whole, its front faces one aggregate occluder. Each casts a
// shadow frustum from the eye, without a far plane: side planes through
// the eye and the occluder's edges (its silhouette's, for a box), the
// occluder's plane as near plane (its front faces' planes, for a box);
// a node whose box lies wholly inside one is culled, tested against the
// occluder that culled it last first. Exact for convex occluders, with a
// margin against occlusion (occluders/shadow_volumes.h); skins whose mesh
// the eye may be inside, or whose mesh's surface the near plane may clip,
// are not used.
//
// planes (supporting_plane_culler.cpp) "Shadow Culling" (Coorg and
// Teller): the same occluders; a node is culled when the viewer is inside
// all the supporting planes of an occluder and the node's box (each
// through an occluder edge, or silhouette edge of an aggregate, and a box
// vertex, occluder and box on one side), and in front of the occluder's
// plane with the box behind it. The planes of a pair do not depend on the
// eye, so they are made at the pair's first test and kept across frames
// (plane-cache; an aggregate's per region of viewpoints, as its
// silhouette changes); a frame tests the eye alone. For a single convex
// occluder the answer equals shadow's (shadow_volumes.h shows why;
// tests/unit/occluders/shadow_volumes_test.cpp checks it).
#pragma once

#include "culling/registry.h"

namespace occu::strategies {

StrategyFamily hp_occlusion_test_family();
StrategyFamily hierarchical_z_buffer_family();
StrategyFamily hierarchical_occlusion_map_family();
StrategyFamily shadow_frustum_family();
StrategyFamily supporting_plane_family();

}  // namespace occu::strategies
