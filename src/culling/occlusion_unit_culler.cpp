#include "culling/occlusion_unit_culler.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "gl/extensions.h"
#include "render/scene_renderer.h"
#include "spatial/hierarchy.h"

namespace occu {

OcclusionUnitCuller::OcclusionUnitCuller(const CullerOptions &options, bool shared_passes)
    : renderer_(options.renderer), leaf_geometry_(options.leaf_geometry), threshold_(options.adaptive_threshold),
      shared_passes_(shared_passes), max_test_area_(options.max_test_area)
{
    if (leaf_geometry_ && !renderer_)
        throw std::invalid_argument("leaf geometry tests need the scene renderer");
    if (!(threshold_ >= 0.0f && threshold_ < 1.0f))
        throw std::invalid_argument("adaptive threshold " + std::to_string(threshold_) + " is outside [0, 1)");
    if (!(max_test_area_ > 0.0 && max_test_area_ <= 1.0))
        throw std::invalid_argument("max test area " + std::to_string(max_test_area_) + " is outside (0, 1]");
    if (!gl::has_extension("GL_MESAX_occlusion_unit"))
        throw std::runtime_error("occu-hier needs GL_MESAX_occlusion_unit, which this context lacks");
    ScissorsMESAX_ = reinterpret_cast<PFNGLSCISSORSMESAXPROC>(gl::get_proc_address("glScissorsMESAX"));
    OcclusionBuffersMESAX_ =
        reinterpret_cast<PFNGLOCCLUSIONBUFFERSMESAXPROC>(gl::get_proc_address("glOcclusionBuffersMESAX"));
}

void OcclusionUnitCuller::begin_frame(const Camera &camera)
{
    camera_ = camera;
    view_projection_ = camera.view_projection();
    frustum_.emplace(view_projection_);
    glGetIntegerv(GL_VIEWPORT, viewport_);
    passes_ = 0;
}

bool OcclusionUnitCuller::screen_rect(const Aabb &box, Rect &rect) const
{
    const auto p = project_box(view_projection_, camera_.position, box);
    if (!p)
        return false;
    const float x0 = p->ndc_min.x, y0 = p->ndc_min.y, x1 = p->ndc_max.x, y1 = p->ndc_max.y;
    // Window pixels whose centres the projection can reach, one more each
    // side for rounding; clamped to the viewport (tiles past it are legal
    // but count nothing).
    auto to_x = [this](float ndc) { return viewport_[0] + (ndc + 1.0f) * 0.5f * float(viewport_[2]); };
    auto to_y = [this](float ndc) { return viewport_[1] + (ndc + 1.0f) * 0.5f * float(viewport_[3]); };
    auto clamp_x = [this](float v) { return GLint(std::clamp(v, float(viewport_[0]), float(viewport_[0] + viewport_[2]))); };
    auto clamp_y = [this](float v) { return GLint(std::clamp(v, float(viewport_[1]), float(viewport_[1] + viewport_[3]))); };
    rect = {clamp_x(std::floor(to_x(x0)) - 1.0f), clamp_y(std::floor(to_y(y0)) - 1.0f),
            clamp_x(std::ceil(to_x(x1)) + 1.0f), clamp_y(std::ceil(to_y(y1)) + 1.0f)};
    return true;
}

double OcclusionUnitCuller::area_fraction(const Rect &r) const
{
    return double(r.x1 - r.x0) * double(r.y1 - r.y0) / (double(viewport_[2]) * double(viewport_[3]));
}

Visibility OcclusionUnitCuller::test(const Aabb &box)
{
    std::vector<Visibility> r;
    test_many({box}, r);
    return r[0];
}

void OcclusionUnitCuller::test_nodes(const Hierarchy &hierarchy, const std::vector<std::uint32_t> &nodes,
                                     const std::vector<Aabb> &boxes, std::vector<Visibility> &results)
{
    hierarchy_ = &hierarchy;
    nodes_ = &nodes;
    test_many(boxes, results);
    hierarchy_ = nullptr;
    nodes_ = nullptr;
}

void OcclusionUnitCuller::test_many(const std::vector<Aabb> &boxes, std::vector<Visibility> &results)
{
    results.assign(boxes.size(), Visibility::visible);
    std::vector<Rect> rects(boxes.size());
    std::vector<std::size_t> pending;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        if (frustum_->classify(boxes[i]) == Frustum::Side::outside)
            results[i] = Visibility::view_culled;
        else if (screen_rect(boxes[i], rects[i]) && area_fraction(rects[i]) <= max_test_area_)
            pending.push_back(i);
    }
    // Greedy passes of boxes with pairwise disjoint rectangles.
    while (!pending.empty()) {
        std::vector<std::size_t> pass, later;
        for (std::size_t i : pending) {
            const Rect &r = rects[i];
            const bool disjoint = pass.size() < records_.size() &&
                                  (shared_passes_ || std::all_of(pass.begin(), pass.end(), [&](std::size_t j) {
                                      const Rect &q = rects[j];
                                      return r.x1 <= q.x0 || q.x1 <= r.x0 || r.y1 <= q.y0 || q.y1 <= r.y0;
                                  }));
            (disjoint ? pass : later).push_back(i);
        }
        run_pass(boxes, pass, rects, results);
        pending.swap(later);
    }
}

void OcclusionUnitCuller::run_pass(const std::vector<Aabb> &boxes, const std::vector<std::size_t> &members,
                                   const std::vector<Rect> &rects, std::vector<Visibility> &results)
{
    const GLsizei n = GLsizei(members.size());
    GLint tiles[64 * 4];
    GLuint *buffers[64];
    GLsizei sizes[64];
    // Each tile grows outwards to whole 64 x 64 blocks of the window where
    // that takes in no other member's rectangle: its counts cannot change
    // (only its own box's fragments fall in it), and llvmpipe sums bins that
    // tiles cover whole without sorting fragments into tiles (its bins are
    // 64 x 64; patch 0004). Growing past the window's edge is clamped.
    constexpr GLint bin = 64;
    const GLint wx0 = viewport_[0], wy0 = viewport_[1], wx1 = wx0 + viewport_[2], wy1 = wy0 + viewport_[3];
    for (GLsizei k = 0; k < n; ++k) {
        Rect r = rects[members[k]];
        Rect grown{std::max(wx0, r.x0 / bin * bin), std::max(wy0, r.y0 / bin * bin),
                   std::min(wx1, (r.x1 + bin - 1) / bin * bin), std::min(wy1, (r.y1 + bin - 1) / bin * bin)};
        const bool alone = std::none_of(members.begin(), members.end(), [&](std::size_t j) {
            const Rect &q = rects[j];
            return j != members[k] && grown.x0 < q.x1 && q.x0 < grown.x1 && grown.y0 < q.y1 && q.y0 < grown.y1;
        });
        if (alone && grown.x0 < grown.x1 && grown.y0 < grown.y1)
            r = grown;
        tiles[4 * k] = r.x0;
        tiles[4 * k + 1] = r.y0;
        tiles[4 * k + 2] = r.x1 - r.x0;
        tiles[4 * k + 3] = r.y1 - r.y0;
        buffers[k] = records_[std::size_t(k)].data();
        sizes[k] = 8;
    }
    // Back faces culled (the paper's precondition for meaningful counts).
    // The proxy must pass wherever what it holds would: content can lie on
    // the box's faces, and far away a few centimetres are below both the
    // depth buffer's and float z's resolution. So the test uses LEQUAL and
    // a polygon offset of a few depth units towards the eye, and the box
    // grows by about a pixel at its distance, so that snapping and edge
    // rules at the silhouette cannot drop a pixel the content covers.
    const GLboolean culling = glIsEnabled(GL_CULL_FACE);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glDepthFunc(GL_LEQUAL);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(-1.0f, -4.0f);
    OcclusionBuffersMESAX_(n, sizes, buffers);
    ScissorsMESAX_(n, tiles);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    const float pixel_per_metre =
        2.0f * std::tan(glm::radians(camera_.fovy_degrees) * 0.5f) / float(std::max(viewport_[3], 1));
    for (std::size_t i : members) {
        if (leaf_geometry_ && nodes_ && hierarchy_ && hierarchy_->nodes()[(*nodes_)[i]].leaf()) {
            renderer_->draw_leaf_flat((*nodes_)[i]);
            continue;
        }
        Aabb grown = boxes[i];
        const glm::vec3 nearest = glm::clamp(camera_.position, grown.min, grown.max);
        const float margin = 0.01f + 1.5f * pixel_per_metre * glm::length(nearest - camera_.position);
        grown.min -= glm::vec3(margin);
        grown.max += glm::vec3(margin);
        SceneRenderer::draw_box(grown);
    }
    glRenderMode(GL_RENDER);
    ScissorsMESAX_(0, nullptr);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDepthFunc(GL_LESS);
    if (!culling)
        glDisable(GL_CULL_FACE);
    ++passes_;
    for (GLsizei k = 0; k < n; ++k) {
        const GLuint nohc = records_[std::size_t(k)][0], phc = records_[std::size_t(k)][1];
        const bool occluded = threshold_ == 0.0f ? nohc == 0 : double(nohc) <= double(threshold_) * double(phc);
        results[members[k]] = occluded ? Visibility::occluded : Visibility::visible;
    }
}

}  // namespace occu
