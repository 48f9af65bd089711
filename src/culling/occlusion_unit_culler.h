// "occu-hier": occlusion tests with GL_MESAX_occlusion_unit, the strategy of
// Bartz, Meissner and Huettner (1998, section 3): render a node's bounding
// box in GL_BRIEF_OCCLUSION_MESAX mode against the depth of what has been
// drawn so far; NOHC = 0 means occluded.
//
// Batching: test_many draws several boxes in one pass, one occlusion tile
// per box, the tile being the box's screen rectangle. A tile counts every
// fragment that falls in it, whichever box it came from, so by default
// boxes share a pass only when their rectangles are disjoint; the others go
// to further passes (greedy, in the order given, at most 64 tiles a pass).
// With shared_passes, overlapping boxes share passes too: another box's
// fragments in a tile can only make its box look visible, never occluded,
// so this stays conservative; it trades culling for fewer passes (strategy
// "occu-hier-shared").
//
// Adaptive culling (paper, section 5): with a threshold t > 0 a box counts
// as occluded when NOHC <= t * PHC, i.e. when at most that fraction of its
// projection is visible. t = 0 is exact and conservative.
//
// Boxes that contain the eye or reach in front of the near plane are
// visible without a query: their rasterized faces need not cover what they
// hold (spec issue 13). So are boxes whose screen rectangle covers more
// than max_test_area of the viewport: testing them costs most (the unit
// counts every fragment of the box) and they are rarely hidden; their
// children are tested instead. 1 tests every box.
//
// Leaf geometry (options.leaf_geometry): a leaf is tested by drawing its own
// triangles in the pass instead of its box. Boxes show above and beside
// occluders where what they hold does not; the triangles are exact (the
// same rasterization that would draw them, tested with LEQUAL and an offset
// towards the eye), at the price of the leaf's vertex work in the pass.
#pragma once

#include <array>
#include <optional>

#include "culling/culler.h"
#include "gl/gl_headers.h"
#include "GL/mesax_occlusion_unit.h"

namespace occu {

class OcclusionUnitCuller final : public Culler {
public:
    // Needs a current context with GL_MESAX_occlusion_unit; throws
    // std::runtime_error otherwise, and std::invalid_argument for a
    // threshold outside [0, 1) or a test area outside (0, 1].
    explicit OcclusionUnitCuller(const CullerOptions &options = {}, bool shared_passes = false);

    std::string_view name() const override { return shared_passes_ ? "occu-hier-shared" : "occu-hier"; }
    bool conservative() const override { return threshold_ == 0.0f; }
    void begin_frame(const Camera &camera) override;
    Visibility test(const Aabb &box) override;
    void test_many(const std::vector<Aabb> &boxes, std::vector<Visibility> &results) override;
    void test_nodes(const Hierarchy &hierarchy, const std::vector<std::uint32_t> &nodes,
                    const std::vector<Aabb> &boxes, std::vector<Visibility> &results) override;
    std::uint32_t passes() const override { return passes_; }

private:
    struct Rect {
        GLint x0, y0, x1, y1;   // window pixels, max exclusive
    };
    // False when the box needs no query (eye inside, near plane crossed).
    bool screen_rect(const Aabb &box, Rect &rect) const;
    double area_fraction(const Rect &rect) const;
    void run_pass(const std::vector<Aabb> &boxes, const std::vector<std::size_t> &members,
                  const std::vector<Rect> &rects, std::vector<Visibility> &results);

    // Set by test_nodes for the batch under test: leaves among `boxes` are
    // drawn as their triangles.
    const Hierarchy *hierarchy_ = nullptr;
    const std::vector<std::uint32_t> *nodes_ = nullptr;
    const SceneRenderer *renderer_ = nullptr;   // leaf geometry only
    bool leaf_geometry_ = false;
    float threshold_;
    bool shared_passes_;
    double max_test_area_;
    Camera camera_;
    glm::mat4 view_projection_{1.0f};
    std::optional<Frustum> frustum_;   // of the frame, built once in begin_frame
    GLint viewport_[4] = {0, 0, 1, 1};
    std::uint32_t passes_ = 0;
    PFNGLSCISSORSMESAXPROC ScissorsMESAX_;
    PFNGLOCCLUSIONBUFFERSMESAXPROC OcclusionBuffersMESAX_;
    std::array<std::array<GLuint, 8>, 64> records_{};
};

}  // namespace occu
