#include "culling/opacity_map_culler.h"

#include <algorithm>
#include <cmath>

#include "culling/traversal.h"

namespace occu {

OpacityMapCuller::OpacityMapCuller(const Hierarchy &hierarchy, const SceneRenderer &renderer,
                                   const OpacityMapOptions &options)
    : hierarchy_(hierarchy), renderer_(renderer), options_(options)
{
    options_.divisor = std::max(1, options_.divisor);
}

void OpacityMapCuller::begin_frame(const Camera &camera)
{
    camera_ = camera;
    view_projection_ = camera.view_projection();
    glGetIntegerv(GL_VIEWPORT, viewport_);
    const int w = viewport_[2], h = viewport_[3], k = options_.divisor;
    map_width_ = w / k;
    map_height_ = h / k;

    // Occluders by projected size: the leaves in the frustum whose boxes
    // subtend the largest solid angle (extent squared over distance squared).
    frustum_.emplace(view_projection_);
    const Frustum &frustum = *frustum_;
    std::vector<std::pair<float, std::uint32_t>> candidates;
    const auto &nodes = hierarchy_.nodes();
    for (std::uint32_t n = 0; n < nodes.size(); ++n) {
        if (!nodes[n].leaf() || frustum.classify(nodes[n].bounds) == Frustum::Side::outside)
            continue;
        const glm::vec3 e = nodes[n].bounds.extent();
        const glm::vec3 nearest = glm::clamp(camera.position, nodes[n].bounds.min, nodes[n].bounds.max);
        const float d2 = std::max(glm::dot(nearest - camera.position, nearest - camera.position), 1e-4f);
        candidates.push_back({-glm::dot(e, e) / d2, n});
    }
    const std::size_t count = std::min(options_.occluders, candidates.size());
    std::partial_sort(candidates.begin(), candidates.begin() + std::ptrdiff_t(count), candidates.end());

    // Their depth only: no colour, lighting or materials (section 3).
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glClear(GL_DEPTH_BUFFER_BIT);
    for (std::size_t i = 0; i < count; ++i)
        renderer_.draw_leaf_flat(candidates[i].second);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    std::vector<float> full(std::size_t(w) * std::size_t(h));
    glReadPixels(viewport_[0], viewport_[1], w, h, GL_DEPTH_COMPONENT, GL_FLOAT, full.data());
    glClear(GL_DEPTH_BUFFER_BIT);

    // Reduce: covered if every pixel is, depth the farthest.
    std::vector<std::uint8_t> covered(std::size_t(map_width_) * std::size_t(map_height_));
    std::vector<float> depth(covered.size());
    for (int my = 0; my < map_height_; ++my)
        for (int mx = 0; mx < map_width_; ++mx) {
            float farthest = 0.0f;
            for (int y = my * k; y < (my + 1) * k; ++y)
                for (int x = mx * k; x < (mx + 1) * k; ++x)
                    farthest = std::max(farthest, full[std::size_t(y) * std::size_t(w) + std::size_t(x)]);
            const std::size_t i = std::size_t(my) * std::size_t(map_width_) + std::size_t(mx);
            covered[i] = farthest < 1.0f;
            // Holes weigh nothing in the depth test: with the exact overlap
            // test no box over a hole gets that far, with the approximate
            // one the holes are what it chose to ignore.
            depth[i] = covered[i] ? farthest : 0.0f;
        }
    opacity_.emplace(map_width_, map_height_, covered);
    depth_.emplace(map_width_, map_height_, std::move(depth));
}

Visibility OpacityMapCuller::test(const Aabb &box)
{
    if (frustum_->classify(box) == Frustum::Side::outside)
        return Visibility::view_culled;
    const auto p = project_box(view_projection_, camera_.position, box);
    if (!p || map_width_ == 0 || map_height_ == 0)
        return Visibility::visible;   // holds the eye or crosses the near plane
    const float x0 = p->ndc_min.x, y0 = p->ndc_min.y, x1 = p->ndc_max.x, y1 = p->ndc_max.y;
    // Map pixels the rectangle touches, widened by one full-resolution pixel
    // for rounding; OPF coordinates: m0 < x <= m1.
    const float k = float(options_.divisor);
    auto map_x = [&](float ndc) { return (ndc + 1.0f) * 0.5f * float(viewport_[2]) / k; };
    auto map_y = [&](float ndc) { return (ndc + 1.0f) * 0.5f * float(viewport_[3]) / k; };
    const float pad = 1.0f / k;
    const int mx0 = std::clamp(int(std::floor(map_x(x0) - pad)), 0, map_width_);
    const int mx1 = std::clamp(int(std::ceil(map_x(x1) + pad)), 0, map_width_);
    const int my0 = std::clamp(int(std::floor(map_y(y0) - pad)), 0, map_height_);
    const int my1 = std::clamp(int(std::ceil(map_y(y1) + pad)), 0, map_height_);
    if (mx0 >= mx1 || my0 >= my1)
        return Visibility::visible;
    if (!opacity_->overlaps_fully(mx0, mx1, my0, my1, options_.tolerance))
        return Visibility::visible;
    // Behind every occluder pixel, with a margin for float z.
    const float z = p->window_z_near - 1e-6f;
    const bool behind = depth_->worthwhile() ? depth_->behind(z, mx0, mx1 - 1, my0, my1 - 1)
                                             : depth_->behind_pixelwise(z, mx0, mx1 - 1, my0, my1 - 1);
    return behind ? Visibility::occluded : Visibility::visible;
}

}  // namespace occu
