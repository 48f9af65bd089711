// Occlusion culling with the opacity map and the sparse depth map (Poon and
// Wang, section 5), by occluder selection (section 6.1, occluder_selection.h):
//   om-ps    occluders by projected size
//   om-fh    occluders by first hit (an ID buffer of the frame)
//   mos-om   occluders from the minimum-occluder-set database of the nearest
//            grid point and heading (preprocessing, occluder_database.h)
//   pc-mos   as mos-om, but the overlap test and depth comparison pixel by
//            pixel (the paper's PC, figure 8), for comparison
//
// begin_frame renders the chosen occluders' depth at full resolution, reads
// it back and reduces it by `divisor` in each direction to the maps'
// resolution (128 x 128 for a 512 x 512 frame): a low-resolution pixel is
// covered only if all its full-resolution pixels are, and its depth is the
// farthest of them, so every test stays conservative. test() then takes
// the box's screen rectangle, widened outwards to whole map pixels: the
// three-operation overlap test (with `tolerance` hole pixels for the
// approximate test), then the sparse depth comparison with the box's
// nearest depth. Boxes that hold the eye or cross the near plane are
// visible.
#pragma once

#include <memory>
#include <optional>

#include "culling/culler.h"
#include "culling/opacity_map.h"
#include "culling/sparse_depth_map.h"
#include "render/scene_renderer.h"
#include "spatial/hierarchy.h"

namespace occu {

class OccluderDatabase;

enum class OccluderCriterion { projected_size, first_hit, minimum_occluder_set };

struct OpacityMapOptions {
    int divisor = 4;                 // full-resolution pixels per map pixel, each way
    std::size_t occluders = 64;      // leaves rendered as occluders
    std::uint32_t tolerance = 0;     // approximate overlap test: hole pixels ignored
    // Adaptive overlap test (section 5.2): a box whose rectangle the
    // occluders cover less than this fraction of is visible and its
    // descendants are not tested (they are drawn). 0: off.
    double coverage_ratio = 0.2;
    OccluderCriterion criterion = OccluderCriterion::projected_size;
    const OccluderDatabase *database = nullptr;   // minimum_occluder_set: required
    bool pixelwise = false;          // PC: compare pixel by pixel instead of OM + SDM
};

class OpacityMapCuller final : public Culler {
public:
    // Draws with `renderer` into the current context (needs GL).
    OpacityMapCuller(const Hierarchy &hierarchy, const SceneRenderer &renderer, const OpacityMapOptions &options = {});

    std::string_view name() const override;
    bool conservative() const override { return options_.tolerance == 0; }
    void begin_frame(const Camera &camera) override;
    Visibility test(const Aabb &box) override;
    std::uint32_t passes() const override { return 1; }

private:
    const Hierarchy &hierarchy_;
    const SceneRenderer &renderer_;
    OpacityMapOptions options_;
    Camera camera_;
    glm::mat4 view_projection_{1.0f};
    std::optional<Frustum> frustum_;   // of the frame, built once in begin_frame
    GLint viewport_[4] = {0, 0, 1, 1};
    int map_width_ = 0, map_height_ = 0;
    std::optional<OpacityMap> opacity_;
    std::optional<SparseDepthMap> depth_;
    std::vector<std::uint8_t> covered_;   // PC: the map's pixels, row by row
    std::vector<std::uint32_t> choose_occluders(const Camera &camera);
};

}  // namespace occu
