#include "culling/opacity_map_culler.h"

#include <algorithm>
#include <cmath>

#include "culling/occluder_selection.h"
#include "culling/traversal.h"
#include "mos/occluder_database.h"

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

    frustum_.emplace(view_projection_);
    const std::vector<std::uint32_t> occluders = choose_occluders(camera);

    // Their depth only: no colour, lighting or materials (section 3).
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glClear(GL_DEPTH_BUFFER_BIT);
    for (std::uint32_t n : occluders)
        renderer_.draw_leaf_flat(n);
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
    if (options_.pixelwise)
        covered_ = std::move(covered);
    depth_.emplace(map_width_, map_height_, std::move(depth));
}

std::string_view OpacityMapCuller::name() const
{
    switch (options_.criterion) {
    case OccluderCriterion::projected_size: return options_.pixelwise ? "pc-ps" : "om-ps";
    case OccluderCriterion::first_hit: return options_.pixelwise ? "pc-fh" : "om-fh";
    case OccluderCriterion::minimum_occluder_set: break;
    }
    return options_.pixelwise ? "pc-mos" : "mos-om";
}

std::vector<std::uint32_t> OpacityMapCuller::choose_occluders(const Camera &camera)
{
    switch (options_.criterion) {
    case OccluderCriterion::projected_size:
        return occluders_by_projected_size(hierarchy_, camera, *frustum_, options_.occluders);
    case OccluderCriterion::first_hit:
        // The ID buffer at the maps' resolution: a first-hit count needs no more.
    {
        auto chosen = occluders_by_first_hit(renderer_, hierarchy_, camera, *frustum_, map_width_, map_height_,
                                             options_.occluders);
        glClear(GL_COLOR_BUFFER_BIT);   // the ID buffer was drawn over the caller's cleared frame
        return chosen;
    }
    case OccluderCriterion::minimum_occluder_set: break;
    }
    std::vector<std::uint32_t> chosen;
    const auto &nodes = hierarchy_.nodes();
    const std::vector<std::uint32_t> listed = options_.database->occluders_for(camera);
    for (std::uint32_t n : listed) {
        if (chosen.size() >= options_.occluders)
            break;
        if (n < nodes.size() && nodes[n].leaf() && frustum_->classify(nodes[n].bounds) != Frustum::Side::outside)
            chosen.push_back(n);
    }
    return chosen;
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
    // Behind every occluder pixel, with a margin for float z.
    const float z = p->window_z_near - 1e-6f;
    if (options_.pixelwise) {
        std::uint32_t holes = 0;
        for (int y = my0; y < my1; ++y)
            for (int x = mx0; x < mx1; ++x)
                holes += !covered_[std::size_t(y) * std::size_t(map_width_) + std::size_t(x)];
        if (holes > options_.tolerance) {
            const double ratio = 1.0 - double(holes) / double((mx1 - mx0) * (my1 - my0));
            return ratio < options_.coverage_ratio ? Visibility::visible_subtree : Visibility::visible;
        }
        return depth_->behind_pixelwise(z, mx0, mx1 - 1, my0, my1 - 1) ? Visibility::occluded
                                                                       : Visibility::visible;
    }
    if (!opacity_->overlaps_fully(mx0, mx1, my0, my1, options_.tolerance))
        return opacity_->coverage_ratio(mx0, mx1, my0, my1) < options_.coverage_ratio ? Visibility::visible_subtree
                                                                                      : Visibility::visible;
    const bool behind = depth_->worthwhile() ? depth_->behind(z, mx0, mx1 - 1, my0, my1 - 1)
                                             : depth_->behind_pixelwise(z, mx0, mx1 - 1, my0, my1 - 1);
    return behind ? Visibility::occluded : Visibility::visible;
}

}  // namespace occu
