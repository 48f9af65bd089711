// SPDX-License-Identifier: MIT
#include "strategies/wonka_view_cells/family.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "gl/occlusion_unit.h"
#include "scene/scene.h"
#include "spatial/hierarchy.h"
#include "strategies/wonka_view_cells/pvs_database.h"
#include "strategies/wonka_view_cells/view_cell_visibility.h"

namespace occu::strategies {

namespace {

ViewCellOptions cell_options(const Settings &settings)
{
    ViewCellOptions cells;
    cells.max_edge = settings.number("max-edge");
    cells.top = settings.number("cell-top");
    cells.clearance = settings.number("clearance");
    return cells;
}

ViewCellVisibilityOptions visibility_options(const Settings &settings)
{
    ViewCellVisibilityOptions options;
    options.epsilon = settings.number("epsilon");
    options.pixel = settings.number("pixel");
    options.initial_extent = settings.number("initial-extent");
    return options;
}

CullMapTest cull_map_test()
{
    return gl::OcclusionUnit::available() ? CullMapTest::occlusion_unit : CullMapTest::readback;
}

class ViewCellCuller final : public Culler {
public:
    ViewCellCuller(const StrategyContext &context, const Settings &settings) : hierarchy_(context.hierarchy)
    {
        for (const HierarchyNode &n : hierarchy_.nodes())
            if (n.leaf())
                scene_triangles_ += n.triangle_count;
        const std::string &path = settings.text("pvs-database");
        if (!path.empty()) {
            database_.emplace(PvsDatabase::load(path));
            if (const std::string mismatch = database_->provenance.mismatch(scene_provenance(context.hierarchy));
                !mismatch.empty())
                throw std::runtime_error(path + ": " + mismatch);
            // The database was made with its own settings (its provenance):
            // one given beside it that differs would be silently ignored.
            const ViewCellOptions &cells = database_->cell_options;
            const ViewCellVisibilityOptions &visibility = database_->visibility_options;
            const std::pair<const char *, double> made_with[] = {
                {"epsilon", visibility.epsilon}, {"pixel", visibility.pixel}, {"max-edge", cells.max_edge},
                {"cell-top", cells.top},         {"clearance", cells.clearance},
                {"initial-extent", visibility.initial_extent}};
            for (const auto &[key, value] : made_with)
                if ((":" + settings.changed()).find(":" + std::string(key) + "=") != std::string::npos &&
                    settings.number(key) != value)
                    throw std::invalid_argument("pvs: " + std::string(key) + "=" + settings.text(key) +
                                                " is not what " + path + " was made with (" + std::to_string(value) +
                                                "): it is the database's to say; give it to occu-preprocess "
                                                "view-cells, not beside pvs-database");
            cells_.emplace(database_->cells, database_->cell_options);
        } else {
            const Scene &scene = context.scene;
            cells_.emplace(glm::dvec2(scene.bounds.min.x, scene.bounds.min.z),
                           glm::dvec2(scene.bounds.max.x, scene.bounds.max.z), scene.prism_occluders,
                           cell_options(settings));
            visibility_.emplace(scene, hierarchy_, *cells_, visibility_options(settings));
            test_ = cull_map_test();
        }
    }

    void begin_frame(const Frame &frame) override
    {
        frustum_.emplace(frame.frustum);
        ++frames_;
        cell_.reset();
        // The near plane must not reach a wall from any eye of a cell: its
        // farthest corner stays within the cells' clearance.
        const Camera &c = frame.camera;
        const double t = std::tan(glm::radians(double(c.fovy_degrees)) / 2.0);
        const double reach = double(c.near_plane) * std::sqrt(1.0 + t * t * (1.0 + double(c.aspect) * double(c.aspect)));
        if (reach > cells_->options().clearance) {
            ++frames_near_plane_;
            return;   // view-frustum culling this frame
        }
        const std::optional<std::uint32_t> cell = cells_->locate(c.position);
        const std::vector<std::uint32_t> *set = nullptr;
        if (cell && database_) {
            const auto it = database_->visible.find(*cell);
            if (it != database_->visible.end())
                set = &it->second;
            else
                ++frames_missing_;   // a shard's database without this cell
        } else if (cell) {
            auto it = made_.find(*cell);
            if (it == made_.end())
                it = made_.emplace(*cell, visibility_->compute(*cell, test_).visible_leaves).first;
            set = &it->second;
        } else {
            ++frames_outside_;
        }
        if (!set)
            return;   // view-frustum culling this frame
        cell_ = cell;
        ++frames_in_cells_;
        const auto &nodes = hierarchy_.nodes();
        for (std::uint32_t leaf : *set)
            if (leaf < nodes.size())
                set_triangles_ += nodes[leaf].triangle_count;
        shows_ = subtrees_holding(hierarchy_, *set);
    }

    void test(std::vector<NodeTest> &tests) override
    {
        for (NodeTest &t : tests) {
            if (frustum_->classify(t.box) == Frustum::Side::outside)
                t.result = Visibility::view_culled;
            else
                t.result = !cell_ || shows_[t.node] ? Visibility::visible : Visibility::occluded;
        }
    }

    std::string note() const override
    {
        std::string s = std::to_string(frames_outside_) + " of " + std::to_string(frames_) +
                        " frames with the eye in no view cell (view-frustum culling there)";
        if (frames_in_cells_ && scene_triangles_) {
            char share[96];
            std::snprintf(share, sizeof(share), "; in cells, the set held %.3f%% of the scene's triangles (%.3f%% occluded)",
                          100.0 * set_triangles_ / double(frames_in_cells_) / scene_triangles_,
                          100.0 - 100.0 * set_triangles_ / double(frames_in_cells_) / scene_triangles_);
            s += share;
        }
        if (frames_near_plane_)
            s += "; " + std::to_string(frames_near_plane_) + " with a near plane reaching past the cells' clearance of " +
                 std::to_string(cells_->options().clearance) + " m (view-frustum culling)";
        if (frames_missing_)
            s += "; " + std::to_string(frames_missing_) + " in cells the database lacks (view-frustum culling)";
        if (visibility_)
            s += "; " + std::to_string(made_.size()) + " cells' sets made during the run (no pvs-database)";
        return s;
    }

private:
    const Hierarchy &hierarchy_;
    std::optional<PvsDatabase> database_;
    std::optional<ViewCells> cells_;
    std::optional<ViewCellVisibility> visibility_;
    CullMapTest test_ = CullMapTest::readback;
    std::map<std::uint32_t, std::vector<std::uint32_t>> made_;
    std::optional<Frustum> frustum_;
    std::optional<std::uint32_t> cell_;
    std::vector<std::uint8_t> shows_;
    std::size_t frames_ = 0, frames_outside_ = 0, frames_missing_ = 0, frames_near_plane_ = 0, frames_in_cells_ = 0;
    double scene_triangles_ = 0, set_triangles_ = 0;   // for the share of the scene the sets hold
};

}  // namespace

StrategyFamily view_cell_family()
{
    using Role = SettingSpec::Role;
    StrategyFamily f;
    f.name = "pvs";
    f.paper = "Wonka, Wimmer and Schmalstieg, sections 2-7";
    f.summary = "the eye's view cell's potentially visible set (cull maps of shrunk occluders), cut by the frustum";
    f.settings = {
        path_setting("pvs-database", "the sets (occu-preprocess view-cells); without one a cell's set is made when "
                                     "the eye first enters it, with the settings below"),
        number_setting("epsilon", 1.0, 0.01, 100.0, Role::cost,
                       "sample spacing and occluder shrinking, metres: smaller is tighter and slower"),
        number_setting("pixel", 1.0, 0.01, 100.0, Role::cost,
                       "cull map pixel, metres (at most epsilon * sqrt(2)): smaller is tighter and slower"),
        number_setting("max-edge", 24.0, 0.5, 10000.0, Role::cost, "longest view cell edge, metres"),
        number_setting("cell-top", 2.0, 0.01, 10000.0, Role::choice, "the view cells' height, metres"),
        number_setting("clearance", 1.0, 0.0, 10000.0, Role::choice,
                       "metres between the cells and the buildings: a frame whose near plane reaches farther is "
                       "view-frustum culled"),
        number_setting("initial-extent", 64.0, 1.0, 1e6, Role::cost,
                       "metres around a cell of its first cull map (section 6)"),
    };
    f.scene_requirements = {{"2.5D occluders (building footprints with heights, Wonka et al. section 4.1), which "
                             "only the generated city provides",
                             [](const Scene &scene) { return !scene.prism_occluders.empty(); }}};
    DatabaseNeed sets;
    sets.setting = "pvs-database";
    sets.name = "PVS database";
    sets.provenance = [](const DatabaseRequest &r) {
        return PvsDatabase::start(r.context.hierarchy, cell_options(r.settings), visibility_options(r.settings))
            .provenance;
    };
    sets.make = [](const DatabaseRequest &r, const std::string &path) {
        PvsDatabase::make(r.context.scene, r.context.hierarchy, cell_options(r.settings), visibility_options(r.settings),
                          cull_map_test())
            .save(path);
    };
    f.databases = {sets};
    f.make = [](const StrategyContext &context, const Settings &settings) -> std::unique_ptr<Culler> {
        return std::make_unique<ViewCellCuller>(context, settings);
    };
    return f;
}

}  // namespace occu::strategies
