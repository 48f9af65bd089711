// SPDX-License-Identifier: MIT
// The potentially visible set of a view cell: Wonka, Wimmer and
// Schmalstieg, "Visibility Preprocessing with Occluder Fusion for Urban
// Walkthroughs" (2000), sections 2.4 ("Algorithm Overview"), 5
// ("Rendering and Merging Occluder Shadows") and 6 ("Hierarchical
// Occlusion Test").
//
// Per cell (section 2.4): the occluders (the scene's prism occluders,
// shrunk by epsilon once, footprint_shrinking.h) cast their
// shadows from every sample point of the cell's top edges into a cull map
// (cull_map.h), fused by the depth and stencil tests; then
// every object (a hierarchy leaf's box) is tested against the map.
//
// Hierarchically (section 6): the first map covers the cell and
// `initial_extent` metres around it; each next one doubles that, up to the
// whole ground. At the border of a map its heights are the cull map
// horizon: an object not wholly inside the map is hidden when every sight
// line from the cell to it crosses the border below the horizon. occu
// takes the border pixels that meet the convex hull of the cell's and the
// object's boxes (every such sight line crosses the border there, no
// higher than the higher of the cell's top and the object's top) and asks
// that each hold an umbra at least that high; the paper's test with three
// supporting planes is a finer version of the same channel. Objects the
// map and the horizon settle are done ("early break" when all are); the
// others go on to the next map. Occluders outside a map cannot shade it
// (their shadows point away from the cell), so each map draws only the
// occluders that meet it.
//
// Conservative for every eye in the cell's prism when epsilon >= k sqrt(2)
// / 2 (section 2.2, enforced): the options refuse a smaller epsilon.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "gl/occlusion_unit.h"
#include "scene/scene.h"
#include "spatial/hierarchy.h"
#include "strategies/wonka_view_cells/cull_map.h"
#include "strategies/wonka_view_cells/view_cells.h"

namespace occu {

enum class CullMapTest {
    readback,         // the paper's: the map copied to main memory, compared on the CPU
    occlusion_unit,   // boxes' tops in brief passes, one tile each; only the horizon ring is read
};
const char *cull_map_test_name(CullMapTest test);

struct ViewCellVisibilityOptions {
    double epsilon = 1.0;          // metres: sample spacing and occluder shrinking (the paper: 1 m)
    double pixel = 1.0;            // the cull map's k, metres; epsilon >= k sqrt(2) / 2
    double initial_extent = 64.0;  // metres around the cell of the first map (the paper: 100 m x 100 m)
};

struct CellVisibility {
    std::vector<std::uint32_t> visible_leaves;   // hierarchy node indices, ascending
    std::size_t maps = 0;            // cull maps drawn (1 + growths)
    std::size_t sample_points = 0;
    std::size_t occluders = 0;       // shrunk occluder parts drawn, summed over the maps
    std::size_t unit_passes = 0;     // brief passes (occlusion_unit test)
    std::size_t map_pixels = 0;      // of the last map
    double map_ms = 0.0;             // drawing the maps
    double test_ms = 0.0;            // testing the objects (read-back or passes, and the horizon)
    double horizon_ms = 0.0;         // of test_ms, section 6's horizon: the same work both ways
};

class ViewCellVisibility {
public:
    // Needs a current context (framebuffer objects, depth clamping;
    // GL_MESAX_occlusion_unit for CullMapTest::occlusion_unit). Throws
    // std::invalid_argument when the scene has no prism occluders (only
    // 2.5D scenes with known solids qualify; a loaded scene has none) or
    // the options break epsilon >= k sqrt(2) / 2 or are not finite and positive.
    ViewCellVisibility(const Scene &scene, const Hierarchy &hierarchy, const ViewCells &cells,
                       const ViewCellVisibilityOptions &options);

    CellVisibility compute(std::size_t cell, CullMapTest test);

    const ViewCellVisibilityOptions &options() const { return options_; }
    std::size_t shrunk_occluders() const { return shrunk_.size(); }

private:
    const Hierarchy &hierarchy_;
    const ViewCells &cells_;
    ViewCellVisibilityOptions options_;
    std::vector<PrismOccluder> shrunk_;
    std::vector<Aabb> shrunk_bounds_;       // x-z extents in min.x/min.z, max.x/max.z
    std::vector<std::uint32_t> leaves_;     // every leaf with a box
    glm::dvec2 ground_min_, ground_max_;
    double top_;                            // the highest object or occluder
    CullMap map_;
    std::optional<gl::OcclusionUnit> unit_;
};

}  // namespace occu
