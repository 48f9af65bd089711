// SPDX-License-Identifier: MIT
#include "strategies/poon_wang_opacity_maps/family.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "gl/framebuffer.h"
#include "gl/state.h"
#include "strategies/poon_wang_opacity_maps/opacity_map.h"
#include "strategies/poon_wang_opacity_maps/sparse_depth_map.h"
#include "strategies/poon_wang_opacity_maps/selection.h"
#include "camera/route.h"
#include "strategies/poon_wang_opacity_maps/occluder_database.h"
#include "strategies/poon_wang_opacity_maps/view_preprocessing.h"
#include "render/id_buffer.h"
#include "render/scene_renderer.h"
#include "spatial/hierarchy.h"
#include "strategies/poon_wang_opacity_maps/occluder_database.h"
#include "strategies/poon_wang_opacity_maps/opacity_map.h"
#include "strategies/poon_wang_opacity_maps/selection.h"
#include "strategies/poon_wang_opacity_maps/sparse_depth_map.h"

namespace occu::strategies {

namespace {

enum class Selection { projected_size, first_hit, minimum_occluder_set };

class OpacityMapCuller final : public Culler {
public:
    OpacityMapCuller(const StrategyContext &context, const Settings &settings)
        : hierarchy_(context.hierarchy), renderer_(context.renderer), ids_(context.renderer),
          occluders_(std::size_t(settings.integer("occluders"))),
          triangle_budget_(std::size_t(settings.integer("occluder-triangle-budget"))),
          tolerance_(std::uint32_t(settings.integer("tolerance"))), coverage_ratio_(settings.number("coverage-ratio")),
          divisor_(int(settings.integer("map-divisor"))), pixelwise_(settings.text("compare") == "pixels")
    {
        const std::string &s = settings.text("selection");
        selection_ = s == "fh" ? Selection::first_hit : s == "mos" ? Selection::minimum_occluder_set
                                                                   : Selection::projected_size;
        const std::string &path = settings.text("database");
        if (selection_ == Selection::minimum_occluder_set) {
            if (path.empty())
                throw std::invalid_argument("selection=mos needs database=FILE (made by occu-preprocess, or on demand "
                                            "by a program's database provider)");
            database_.emplace(OccluderDatabase::load(path));
            const std::string mismatch = database_->provenance.mismatch(scene_provenance(hierarchy_));
            if (!mismatch.empty())
                throw std::runtime_error(path + ": " + mismatch);
        }
    }

    // A switch-off probe (Frame::probe) picks its occluders by projected
    // size, whatever the selection: first hit renders an ID buffer of every
    // leaf in the frustum (section 6.1), a second frame's worth of drawing,
    // 35-55 ms a probe on the city's open route where a probe by projected
    // size costs 2 ms; the probe only asks whether occlusion pays here at
    // all, and the maps of any occluders answer conservatively.
    void begin_frame(const Frame &frame) override
    {
        prepare(frame, frame.probe && selection_ == Selection::first_hit ? Selection::projected_size : selection_);
    }

    void prepare(const Frame &frame, Selection selection)
    {
        frame_.emplace(frame);
        const int w = frame.width, h = frame.height, k = divisor_;
        map_width_ = (w + k - 1) / k;
        map_height_ = (h + k - 1) / k;
        if (database_ && database_->resolution != map_width_)
            throw std::runtime_error("the occluder database was made for maps of " +
                                     std::to_string(database_->resolution) + " pixels, this frame's are " +
                                     std::to_string(map_width_) + " (frame " + std::to_string(w) +
                                     " / map-divisor " + std::to_string(k) + ")");
        const std::vector<std::uint32_t> occluders = choose_occluders(frame, selection);
        const std::vector<float> full = occluder_depth(frame, occluders);

        // Reduce: covered if every frame pixel is, depth the farthest. A
        // map pixel past the frame's edge (width not a multiple of k) takes
        // the frame pixels it has.
        std::vector<std::uint8_t> covered(std::size_t(map_width_) * std::size_t(map_height_));
        std::vector<float> depth(covered.size());
        for (int my = 0; my < map_height_; ++my)
            for (int mx = 0; mx < map_width_; ++mx) {
                float farthest = 0.0f;
                for (int y = my * k; y < std::min(h, (my + 1) * k); ++y)
                    for (int x = mx * k; x < std::min(w, (mx + 1) * k); ++x)
                        farthest = std::max(farthest, full[std::size_t(y) * std::size_t(w) + std::size_t(x)]);
                const std::size_t i = std::size_t(my) * std::size_t(map_width_) + std::size_t(mx);
                covered[i] = farthest < 1.0f;
                // Holes weigh nothing in the depth test: with the exact
                // overlap test no box over a hole gets that far, with the
                // approximate one the holes are what it chose to ignore.
                depth[i] = covered[i] ? farthest : 0.0f;
            }
        opacity_.emplace(map_width_, map_height_, covered);
        if (pixelwise_)
            covered_ = std::move(covered);
        depth_.emplace(map_width_, map_height_, std::move(depth));
        stats_.passes = 1;
    }

    void test(std::vector<NodeTest> &tests) override
    {
        for (NodeTest &t : tests)
            test_one(t);
    }

    CullerStats stats() const override { return stats_; }

private:
    std::vector<std::uint32_t> choose_occluders(const Frame &frame, Selection selection)
    {
        // With a budget in triangles, every candidate in order, then cut.
        const std::size_t limit = triangle_budget_ ? std::numeric_limits<std::size_t>::max() : occluders_;
        std::vector<std::uint32_t> chosen;
        switch (selection) {
        case Selection::projected_size:
            chosen = occluders_by_projected_size(hierarchy_, frame.camera, frame.frustum, limit);
            break;
        case Selection::first_hit:
            // The ID buffer at the maps' resolution: a first-hit count needs no more.
            chosen = occluders_by_first_hit(ids_, hierarchy_, frame.camera, frame.frustum, map_width_, map_height_,
                                            limit);
            break;
        case Selection::minimum_occluder_set: {
            const auto &nodes = hierarchy_.nodes();
            for (std::uint32_t n : database_->occluders_for(frame.camera)) {
                if (chosen.size() >= limit)
                    break;
                if (n < nodes.size() && nodes[n].leaf() &&
                    frame.frustum.classify(nodes[n].bounds) != Frustum::Side::outside)
                    chosen.push_back(n);
            }
            break;
        }
        }
        if (!triangle_budget_)
            return chosen;
        if (leaf_triangles_.empty()) {
            leaf_triangles_.resize(hierarchy_.nodes().size());
            for (std::size_t n = 0; n < leaf_triangles_.size(); ++n)
                leaf_triangles_[n] = hierarchy_.nodes()[n].occluder_triangles;
        }
        return first_leaves_within_triangles(chosen, leaf_triangles_, triangle_budget_);
    }

    // The occluders' window depth at full resolution, drawn into the
    // strategy's own framebuffer: depth only, no colour, lighting or
    // materials (section 3).
    std::vector<float> occluder_depth(const Frame &frame, const std::vector<std::uint32_t> &occluders)
    {
        if (!target_)
            target_.emplace(frame.width, frame.height);
        target_->resize(frame.width, frame.height);
        std::vector<float> full(std::size_t(frame.width) * std::size_t(frame.height));
        gl::Framebuffer::Bind bind(*target_);
        gl::AttribScope state(GL_ENABLE_BIT | GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_POLYGON_BIT);
        gl::MatrixScope matrices;
        gl::load_camera(frame.camera);
        glEnable(GL_DEPTH_TEST);
        glEnable(GL_CULL_FACE);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glClearDepth(1.0);
        glClear(GL_DEPTH_BUFFER_BIT);
        for (std::uint32_t n : occluders)
            renderer_.draw_leaf_flat(n);
        glReadPixels(0, 0, frame.width, frame.height, GL_DEPTH_COMPONENT, GL_FLOAT, full.data());
        return full;
    }

    void test_one(NodeTest &t) const
    {
        const auto footprint = frame_->occlusion_candidate(t);
        if (!footprint)
            return;
        const PixelRect m = footprint->rect.to_map(divisor_).clamped({0, 0, map_width_, map_height_});
        if (m.empty())
            return;
        // Behind every occluder pixel, with a margin for float z.
        const float z = footprint->window_z_near - 1e-6f;
        // OPF coordinates (section 5.2): x1 < x <= x2 over 1-based pixels,
        // i.e. the 0-based pixels x1 .. x2 - 1.
        if (pixelwise_) {
            std::uint32_t holes = 0;
            for (int y = m.y0; y < m.y1; ++y)
                for (int x = m.x0; x < m.x1; ++x)
                    holes += !covered_[std::size_t(y) * std::size_t(map_width_) + std::size_t(x)];
            if (holes > tolerance_) {
                t.test_below = 1.0 - double(holes) / double(m.area()) >= coverage_ratio_;
                return;
            }
            if (depth_->behind_pixelwise(z, m.x0, m.x1 - 1, m.y0, m.y1 - 1))
                t.result = Visibility::occluded;
            return;
        }
        if (!opacity_->overlaps_fully(m.x0, m.x1, m.y0, m.y1, tolerance_)) {
            t.test_below = opacity_->coverage_ratio(m.x0, m.x1, m.y0, m.y1) >= coverage_ratio_;
            return;
        }
        const bool behind = depth_->worthwhile() ? depth_->behind(z, m.x0, m.x1 - 1, m.y0, m.y1 - 1)
                                                 : depth_->behind_pixelwise(z, m.x0, m.x1 - 1, m.y0, m.y1 - 1);
        if (behind)
            t.result = Visibility::occluded;
    }

    const Hierarchy &hierarchy_;
    const SceneRenderer &renderer_;
    IdBuffer ids_;
    std::optional<gl::Framebuffer> target_;
    std::optional<OccluderDatabase> database_;
    Selection selection_ = Selection::projected_size;
    std::size_t occluders_;
    std::size_t triangle_budget_;                 // 0: occluders_ leaves
    std::vector<std::uint32_t> leaf_triangles_;   // per node, its occluder triangles (the budget's count)
    std::uint32_t tolerance_;
    double coverage_ratio_;
    int divisor_;
    bool pixelwise_;
    std::optional<Frame> frame_;
    int map_width_ = 0, map_height_ = 0;
    std::optional<OpacityMap> opacity_;
    std::optional<SparseDepthMap> depth_;
    std::vector<std::uint8_t> covered_;   // compare=pixels: the map's pixels, row by row
    CullerStats stats_;
};

// The minimum-occluder-set database of selection=mos, made on demand as
// occu-preprocess build makes it (section 4: grid points at eye height,
// headings each), for maps of the frame's size / map-divisor.
struct MosDatabase {
    PreprocessOptions options;
    OccluderGrid grid;
    Camera lens;

    explicit MosDatabase(const DatabaseRequest &r)
    {
        const int divisor = int(r.settings.integer("map-divisor"));
        options.stacks.map_divisor = divisor;
        options.stacks.resolution = (std::max(r.width, 1) + divisor - 1) / divisor;
        const Aabb &bounds = r.context.scene.bounds;
        const int points = int(r.settings.integer("database-grid"));
        grid = OccluderGrid::over_scene(bounds, {points, int(r.settings.integer("database-layers")), points},
                                        int(r.settings.integer("database-headings")),
                                        float(r.settings.number("database-eye-height")));
        // The street-level lens, its near plane within a scene smaller than it.
        lens = street_level_lens(bounds, 1.0f);
        const float diagonal = std::max(glm::length(bounds.extent()), 1e-3f);
        lens.near_plane = std::min(lens.near_plane, 1e-3f * diagonal);
        lens.far_plane = 2.0f * diagonal;
    }
};

DatabaseNeed mos_database_need()
{
    DatabaseNeed need;
    need.setting = "database";
    need.name = "occluder database";
    need.required = true;
    need.read_by = [](const Settings &s) { return s.text("selection") == "mos"; };
    need.provenance = [](const DatabaseRequest &r) {
        const MosDatabase m(r);
        return occluder_database_for(r.context.hierarchy, m.grid, m.lens, m.options).provenance;
    };
    need.make = [](const DatabaseRequest &r, const std::string &path) {
        const MosDatabase m(r);
        preprocess_database(r.context.renderer, r.context.hierarchy, m.grid, m.lens, m.options).save(path);
    };
    return need;
}

}  // namespace

StrategyFamily opacity_map_family()
{
    using Role = SettingSpec::Role;
    StrategyFamily f;
    f.name = "om";
    f.paper = "Poon and Wang, sections 4, 5 and 6.1";
    f.summary = "opacity map and sparse depth map of selected occluders, tested on the CPU";
    f.traversal.switch_off = true;
    f.settings = {
        choice_setting("selection", {"ps", "fh", "mos"},
                       "occluders by projected size, first hit, or from a minimum-occluder-set database"),
        choice_setting("compare", {"maps", "pixels"}, "overlap and depth tests on the maps (OM + SDM) or per pixel (PC)"),
        integer_setting("occluders", 64, 1, 1 << 20, Role::cost, "leaves rendered as occluders each frame"),
        integer_setting("occluder-triangle-budget", 0, 0, 1 << 24, Role::cost,
                        "instead of `occluders` leaves, the best leaves up to this many triangles in all, so that "
                        "smaller leaves do not shrink the occluders' share of the scene",
                        "0"),
        integer_setting("tolerance", 0, 0, 1 << 20, Role::approximation,
                        "approximate overlap test: map pixels of holes ignored"),
        number_setting("coverage-ratio", 0.2, 0.0, 1.0, Role::cost,
                       "adaptive overlap test: below this coverage a box's descendants go untested", "0"),
        integer_setting("map-divisor", 4, 1, 64, Role::cost, "frame pixels per map pixel, each way"),
        path_setting("database", "the occluder database for selection=mos (occu-preprocess build); without one, "
                                 "made on demand with the settings below"),
        integer_setting("database-grid", 8, 1, 256, Role::choice,
                        "a database made on demand: grid points each way across the scene's ground"),
        integer_setting("database-layers", 1, 1, 64, Role::choice,
                        "a database made on demand: layers of grid points, from eye height to that above the top"),
        integer_setting("database-headings", 8, 1, 64, Role::choice,
                        "a database made on demand: view headings at each grid point"),
        number_setting("database-eye-height", 1.7, 0.0, 1e6, Role::choice,
                       "a database made on demand: metres above the scene's floor of its lowest grid points"),
    };
    f.databases = {mos_database_need()};
    f.presets = {
        {"om-ps", "selection=ps"},
        {"om-fh", "selection=fh"},
        {"om-mos", "selection=mos"},
        {"pc-ps", "selection=ps:compare=pixels"},
        {"pc-fh", "selection=fh:compare=pixels"},
        {"pc-mos", "selection=mos:compare=pixels"},
        {"mos-om", "selection=mos", true},
    };
    // Temporal coherence; occluders chosen by a triangle budget; first-hit
    // selection (section 4) with the switch-off's probes, on the maps and
    // per pixel.
    f.test_variants = {
        StrategyTestVariant("om-ps").with_coherence(),
        StrategyTestVariant("om-ps:occluder-triangle-budget=2048"),
        StrategyTestVariant("om-fh").with_probing_switch_off(),
        StrategyTestVariant("pc-fh").with_probing_switch_off(),
    };
    f.make = [](const StrategyContext &context, const Settings &settings) -> std::unique_ptr<Culler> {
        return std::make_unique<OpacityMapCuller>(context, settings);
    };
    return f;
}

}  // namespace occu::strategies
