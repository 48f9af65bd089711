// SPDX-License-Identifier: MIT
#include "strategies/poon_wang_opacity_maps/view_preprocessing.h"

#include <sstream>

#include "strategies/poon_wang_opacity_maps/minimum_occluder_set.h"
#include "strategies/poon_wang_opacity_maps/occluder_scoring.h"

namespace occu {

std::string PreprocessOptions::describe() const
{
    std::ostringstream s;
    s << "resolution=" << stacks.resolution << " map-divisor=" << stacks.map_divisor
      << " min-occludee-triangles=" << stacks.min_occludee_triangles
      << " min-occluder-pixels=" << stacks.min_occluder_pixels << " max-occluders=" << max_occluders
      << " sets-per-occludee=" << sets_per_occludee << " step-budget=" << step_budget
      << " pixels-per-occluder=" << pixels_per_occluder << " selection=" << (marginal_scores ? "marginal" : "static");
    return s.str();
}

std::vector<std::uint32_t> select_occluders_for_view(const SceneRenderer &renderer, const Hierarchy &hierarchy,
                                                     const Camera &camera, const PreprocessOptions &options,
                                                     PreprocessStats *stats)
{
    PreprocessStats local;
    PreprocessStats &st = stats ? *stats : local;
    const std::size_t nodes = hierarchy.nodes().size();

    // 4.1
    ViewOccluders view = build_occluder_stacks(renderer, hierarchy, camera, options.stacks);
    st.occludees = std::uint32_t(view.occludees.size());
    st.candidates = std::uint32_t(view.candidates.size());
    st.passes = view.passes;

    // 4.2
    MosSearchOptions search;
    search.cost.assign(nodes, 1.0);
    for (std::uint32_t c : view.candidates)
        search.cost[c] = 1.0 + double(view.pixels[c]) / options.pixels_per_occluder;
    search.keep_cheapest = options.sets_per_occludee;
    search.step_budget = options.step_budget;
    std::vector<std::vector<OccluderSet>> sets_of;   // per coverable occludee
    for (Occludee &o : view.occludees) {
        const auto table = combination_table(o.stack);
        o.stack.clear();
        if (table.empty())
            continue;
        MosSearchResult r = minimum_occluder_sets(table, search);
        st.searches_cut += !r.complete;
        if (r.sets.empty())
            continue;
        ++st.coverable;
        sets_of.push_back(std::move(r.sets));
    }

    // 4.3
    ScoredSets scored = score_sets(sets_of, search.cost);
    st.sets = std::uint32_t(scored.sets.size());
    std::vector<OccluderSet> ordered;
    if (options.marginal_scores) {
        for (std::size_t i : order_by_marginal_score(scored.sets, sets_of, search.cost))
            ordered.push_back(scored.sets[i]);
    } else {
        ordered = std::move(scored.sets);
    }
    IdBuffer ids(renderer);
    return select_without_redundancy(ids, camera, ordered, nodes, options.stacks.resolution, options.max_occluders);
}

OccluderDatabase occluder_database_for(const Hierarchy &hierarchy, const OccluderGrid &grid, const Camera &lens,
                                       const PreprocessOptions &options)
{
    OccluderDatabase db;
    db.provenance = DatabaseProvenance::current(
        "minimum-occluder-set",
        options.describe() + " " + grid_settings(grid) + " lens=" + exact_number(lens.fovy_degrees) + "," +
            exact_number(lens.aspect) + "," + exact_number(lens.near_plane) + "," + exact_number(lens.far_plane),
        scene_provenance(hierarchy), true);
    db.grid = grid;
    db.resolution = options.stacks.resolution;
    return db;
}

OccluderDatabase preprocess_database(const SceneRenderer &renderer, const Hierarchy &hierarchy, const OccluderGrid &grid,
                                     const Camera &lens, const PreprocessOptions &options)
{
    OccluderDatabase db = occluder_database_for(hierarchy, grid, lens, options);
    const OccluderGrid &g = db.grid;
    for (std::uint32_t v = 0; v < g.view_count(); ++v)
        db.views[v] = select_occluders_for_view(renderer, hierarchy, g.view_camera(v, lens), options);
    return db;
}

}  // namespace occu
