// SPDX-License-Identifier: MIT
// occu-preprocess: builds the minimum-occluder-set database that the
// walkthrough's om-mos strategy reads (Poon and Wang, section 4; the steps
// are in src/strategies/poon_wang_opacity_maps/view_preprocessing.h).
//
//   occu-preprocess build (--out FILE | --cache DIR) [--scene city|field|FILE] [--city-copies N]
//                   [--leaf-triangles N|auto] [--grid NX,NY,NZ] [--directions D]
//                   [--eye-height H] [--max-occluders N] [--resolution R] [--map-divisor K]
//                   [--selection marginal|static] [--pixels-per-occluder P]
//                   [--shard I/N] [--driver llvmpipe|softpipe]
//   occu-preprocess merge --out FILE SHARD...
//   occu-preprocess views --out ROUTE [--every K] DATABASE
//   occu-preprocess skins --out FILE [--scene city|field|FILE] [--city-copies N] [--voxel-size V]
//                   [--max-boxes N] [--min-volume M] [--start densest|first] [--shard I/N]
//   occu-preprocess view-cells --out FILE [--city-copies N] [--leaf-triangles N|auto]
//                   [--epsilon E] [--pixel K] [--max-edge M] [--cell-top T] [--clearance C] [--initial-extent X]
//                   [--test occlusion-unit|readback|both] [--cells FIRST-LAST]
//                   [--route R [--frames N]] [--shard I/N] [--driver llvmpipe|softpipe]
//
// --cache DIR names the database by its key (DatabaseProvenance::key: the
// library's code, the options with the grid and lens, scene, hierarchy and Mesa build),
// makes it only if DIR holds no database of that key, and prints its path
// on stdout (the rest goes to stderr). --resolution R and --map-divisor K:
// the run-time maps the database serves (R x R maps of a frame of R * K
// pixels; the walkthrough's defaults are 128 and 4).
// --selection static keeps the paper's fixed scores (section 4.3) instead of the
// greedy marginal order (strategies/poon_wang_opacity_maps/occluder_scoring.h).
// --pixels-per-occluder P weighs an occluder's cost: 1 + its pixels (at
// --resolution) / P (16384); a large P counts occluders, a small one their
// rasterization.
//
// Grid points span the scene's ground rectangle corner to corner at eye
// height (for the default city, 8 x 8 points are its street crossings);
// each has D headings. `views` writes a route file (camera/route.h) of the
// database's views as preprocessing placed them: every K-th view with
// occluders at the inner points (the outer ones look out of the city or
// along its edge), for measuring selection at viewpoints (bench/occluders.sh).
// --shard I/N processes the views v with v % N == I - 1, so N
// machines (under any job scheduler) each write a shard; merge joins them.
// The scene options must match the walkthrough's: the database records
// what it was made for (occluder_database.h), and the walkthrough refuses a
// database made for another scene, hierarchy, map resolution or Mesa.
//
// `skins` makes the occluder skins of the scene's meshes (Leone et al.,
// section 4; occluders/occluder_skins.h, which
// describes the file and the options: voxel edge in metres, boxes per mesh,
// the smallest box in m^3 and where boxes start growing). Pure geometry: no GL, no Mesa. Meshes without
// skins (not watertight, no interior at that voxel size) are listed on
// stderr and recorded in the file; they do not make the command fail.
// --shard I/N takes the meshes m with m % N == I - 1. `merge` joins skin
// shards as well: it tells the kinds of file by their first line, and
// all its shards must be of the kind of the first.
//
// `view-cells` precomputes the potentially visible set of every view cell
// (Wonka, Wimmer and Schmalstieg 2000; strategies/wonka_view_cells/:
// view_cell_visibility.h and pvs_database.h): cells over the city's streets with edges of at most
// --max-edge m kept --clearance m from the buildings, prisms up to
// --cell-top m, sample points --epsilon apart,
// occluders shrunk by epsilon, cull maps of --pixel m pixels growing from
// --initial-extent m around the cell. --test picks how objects are tested
// against a cull map: with the Occlusion Unit (the default) or by reading
// the map back (the paper's); `both` does each per cell, checks that they
// find the same visible leaves (failing otherwise) and reports the time of
// each. --cells FIRST-LAST makes only those cells, --route R (with
// --frames N, as the walkthrough's) only the cells its cameras are in (a
// quick look, or a database for measuring a route of a large city; the
// others are missing from the database, and pvs view-frustum culls in
// them). --shard I/N takes the cells c with c % N == I - 1; `merge` joins
// PVS shards too. Only the generated city qualifies: a loaded scene has no
// known 2.5D occluders (--scene is refused, saying so).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "camera/route.h"
#include "cli/arguments.h"
#include "cli/progress.h"
#include "evaluation/scene_setup.h"
#include "gl/extensions.h"
#include "gl/offscreen_context.h"
#include "occluders/occluder_skins.h"
#include "render/scene_renderer.h"
#include "scene/city.h"
#include "scene/scene_file.h"
#include "spatial/hierarchy.h"
#include "strategies/poon_wang_opacity_maps/occluder_database.h"
#include "strategies/poon_wang_opacity_maps/view_preprocessing.h"
#include "strategies/wonka_view_cells/pvs_database.h"
#include "strategies/wonka_view_cells/view_cell_visibility.h"

namespace {

[[noreturn]] void usage(const std::string &error)
{
    std::fprintf(error.empty() ? stdout : stderr,
                 "%s%susage: occu-preprocess build (--out FILE | --cache DIR) [--scene city|field|FILE] [--city-copies N]\n"
                 "                       [--leaf-triangles N|auto] [--grid NX,NY,NZ] [--directions D] [--eye-height H]\n"
                 "                       [--max-occluders N] [--resolution R] [--map-divisor K]\n"
                 "                       [--selection marginal|static] [--pixels-per-occluder P]\n"
                 "                       [--shard I/N] [--driver llvmpipe|softpipe]\n"
                 "       occu-preprocess merge --out FILE SHARD...\n"
                 "       occu-preprocess views --out ROUTE [--every K] DATABASE\n"
                 "       occu-preprocess skins --out FILE [--scene city|field|FILE] [--city-copies N] [--voxel-size V]\n"
                 "                       [--max-boxes N] [--min-volume M] [--start densest|first] [--shard I/N]\n"
                 "       occu-preprocess view-cells --out FILE [--city-copies N] [--leaf-triangles N|auto] [--epsilon E]\n"
                 "                       [--pixel K] [--max-edge M] [--cell-top T] [--clearance C] [--initial-extent X]\n"
                 "                       [--test occlusion-unit|readback|both] [--cells FIRST-LAST]\n"
                 "                       [--route R [--frames N]] [--shard I/N] [--driver llvmpipe|softpipe]\n",
                 error.empty() ? "" : "occu-preprocess: ", error.empty() ? "" : (error + "\n").c_str());
    std::exit(error.empty() ? 0 : 2);
}

struct Options {
    std::string out, cache, scene, driver = "llvmpipe";
    int city_copies = 1, directions = 8, shard = 1, shards = 1;
    std::uint32_t leaf_triangles = occu::HierarchyOptions{}.max_leaf_triangles;
    glm::ivec3 grid{8, 1, 8};
    float eye_height = 1.7f;
    occu::PreprocessOptions pre;
    std::vector<std::string> inputs;   // merge, views
    int every = 1;                     // views
    occu::SkinOptions skins;           // skins
    occu::ViewCellOptions cells;       // view-cells
    occu::ViewCellVisibilityOptions visibility;
    std::string test = "occlusion-unit";
    std::uint32_t first_cell = 0, last_cell = 0xFFFFFFFFu;   // view-cells --cells
    std::string route;                 // view-cells --route: only the cells its cameras are in
    int route_frames = 60;
};

// What kind of database `path` is (culling/database_file.h).
std::string kind_of(const std::string &path)
{
    return occu::DatabaseReader(path, "", 0, "database").kind();
}

int merge_skins(const Options &o)
{
    std::vector<occu::OccluderSkinDatabase> shards;
    for (const auto &path : o.inputs)
        shards.push_back(occu::OccluderSkinDatabase::load(path));
    const auto db = occu::OccluderSkinDatabase::merge(shards, o.inputs);
    db.save(o.out);
    std::printf("%s: skins of %zu of %u meshes from %zu shards\n", o.out.c_str(), db.mesh_count(),
                db.meshes, shards.size());
    return db.mesh_count() == db.meshes ? 0
                                                   : (std::fprintf(stderr, "occu-preprocess: meshes missing\n"), 1);
}

int merge_pvs(const Options &o)
{
    std::vector<occu::PvsDatabase> shards;
    for (const std::string &path : o.inputs)
        shards.push_back(occu::PvsDatabase::load(path));
    const auto db = occu::PvsDatabase::merge(shards, o.inputs);
    db.save(o.out);
    std::printf("%s: visible sets of %zu of %zu view cells from %zu shards\n", o.out.c_str(), db.visible.size(),
                db.cells.size(), shards.size());
    return 0;
}

int merge(const Options &o)
{
    const std::string kind = kind_of(o.inputs.front());
    if (kind == "pvs")
        return merge_pvs(o);
    if (kind == "occluder-skins")
        return merge_skins(o);
    std::vector<occu::OccluderDatabase> shards;
    for (const auto &path : o.inputs)
        shards.push_back(occu::OccluderDatabase::load(path));
    const auto db = occu::OccluderDatabase::merge(shards);
    db.save(o.out);
    std::printf("%s: %zu of %u views from %zu shards\n", o.out.c_str(), db.views.size(), db.grid.view_count(),
                shards.size());
    return db.views.size() == db.grid.view_count() ? 0 : (std::fprintf(stderr, "occu-preprocess: views missing\n"), 1);
}

int views(const Options &o)
{
    const auto db = occu::OccluderDatabase::load(o.inputs.front());
    const occu::OccluderGrid &g = db.grid;
    std::FILE *out = std::fopen(o.out.c_str(), "w");
    if (!out)
        throw std::runtime_error(o.out + ": cannot write");
    std::size_t eligible = 0, written = 0;
    for (const auto &[v, list] : db.views) {
        const std::uint32_t p = v / std::uint32_t(g.directions);
        const int i = int(p % std::uint32_t(g.points.x));
        const int k = int(p / std::uint32_t(g.points.x * g.points.y));
        if (list.empty() || i == 0 || k == 0 || i == g.points.x - 1 || k == g.points.z - 1 || eligible++ % std::size_t(o.every))
            continue;
        const occu::Camera c = g.view_camera(v, occu::Camera{});
        std::fprintf(out, "%.6f %.6f %.6f %.6f %.6f %.6f  # view %u\n", c.position.x, c.position.y, c.position.z,
                     c.target.x, c.target.y, c.target.z, v);
        ++written;
    }
    if (std::fclose(out) != 0)
        throw std::runtime_error(o.out + ": write failed");
    std::printf("%s: %zu views\n", o.out.c_str(), written);
    return written ? 0 : (std::fprintf(stderr, "occu-preprocess: no view with occluders at inner points\n"), 1);
}

int build(const Options &o)
{
    using namespace occu;
    gl::select_driver(gl::parse_driver(o.driver));
    const SceneSetup setup({o.scene, o.city_copies, o.leaf_triangles});
    const Scene &scene = setup.scene();
    const Hierarchy &hierarchy = setup.hierarchy();
    const Camera lens = street_level_lens(scene.bounds, 1.0f);
    OccluderDatabase db = occluder_database_for(
        hierarchy, OccluderGrid::over_scene(scene.bounds, o.grid, o.directions, o.eye_height), lens, o.pre);
    const OccluderGrid &g = db.grid;

    // With --cache the database is named by what it depends on, and made
    // only once.
    std::string path = o.out;
    std::FILE *report = stdout;
    if (!o.cache.empty()) {
        std::filesystem::create_directories(o.cache);
        path = o.cache + "/occluders-" + db.provenance.key() + (o.shards > 1 ? "-shard" + std::to_string(o.shard) + "of" + std::to_string(o.shards) : "") + ".db";
        report = stderr;
        if (std::filesystem::exists(path)) {
            try {
                const OccluderDatabase cached = OccluderDatabase::load(path);
                if (cached.provenance == db.provenance) {
                    std::fprintf(stderr, "occu-preprocess: %s is up to date\n", path.c_str());
                    std::printf("%s\n", path.c_str());
                    return 0;
                }
            } catch (const std::exception &e) {
                std::fprintf(stderr, "occu-preprocess: remaking %s (%s)\n", path.c_str(), e.what());
            }
        }
    }
    gl::OffscreenContext ctx(o.pre.stacks.resolution, o.pre.stacks.resolution);
    if (!gl::has_extension("GL_MESAX_occlusion_unit"))
        throw std::runtime_error(ctx.renderer() + " lacks GL_MESAX_occlusion_unit (run on occu's patched Mesa)");
    SceneRenderer renderer(scene, hierarchy);

    std::vector<std::uint32_t> views;
    for (std::uint32_t v = 0; v < g.view_count(); ++v)
        if (int(v % std::uint32_t(o.shards)) == o.shard - 1)
            views.push_back(v);
    std::fprintf(report, "scene: %zu triangles, %zu leaves; %u views (%d x %d x %d points, %d headings), shard %d/%d: %zu views\n",
                scene.triangle_count(), hierarchy.leaf_count(), g.view_count(), g.points.x, g.points.y, g.points.z,
                g.directions, o.shard, o.shards, views.size());
    const auto start = std::chrono::steady_clock::now();
    PreprocessStats total;
    for (std::size_t i = 0; i < views.size(); ++i) {
        PreprocessStats st;
        const Camera camera = g.view_camera(views[i], lens);
        db.views[views[i]] = select_occluders_for_view(renderer, hierarchy, camera, o.pre, &st);
        total.occludees += st.occludees;
        total.coverable += st.coverable;
        total.passes += st.passes;
        total.sets += st.sets;
        total.searches_cut += st.searches_cut;
        progress("preprocess", long(i + 1), long(views.size()));
    }
    db.save(path);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::size_t occluders = 0;
    for (const auto &[v, list] : db.views)
        occluders += list.size();
    std::fprintf(report, "%s: %zu views in %.1f s; per view %.1f occluders, %.0f occludees (%.0f coverable), "
                "%.0f verbose passes, %.0f distinct sets; %u searches cut by the budget\n",
                path.c_str(), views.size(), s, double(occluders) / double(std::max<std::size_t>(views.size(), 1)),
                double(total.occludees) / double(std::max<std::size_t>(views.size(), 1)),
                double(total.coverable) / double(std::max<std::size_t>(views.size(), 1)),
                double(total.passes) / double(std::max<std::size_t>(views.size(), 1)),
                double(total.sets) / double(std::max<std::size_t>(views.size(), 1)), total.searches_cut);
    if (!o.cache.empty())
        std::printf("%s\n", path.c_str());
    return 0;
}

int skins(const Options &o)
{
    using namespace occu;
    CityOptions city;
    city.copies = o.city_copies;
    const Scene scene = scene_by_name(o.scene, city);
    std::printf("scene: %zu meshes, %zu triangles; %s; shard %d/%d\n", scene.meshes.size(), scene.triangle_count(),
                o.skins.describe().c_str(), o.shard, o.shards);
    const auto start = std::chrono::steady_clock::now();
    const OccluderSkinDatabase db =
        OccluderSkinDatabase::make(scene, o.skins, o.shard, o.shards,
                                   [](std::size_t done, std::size_t total) { progress("skins", long(done), long(total)); });
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    db.save(o.out);
    const std::size_t listed = 20;
    std::size_t k = 0;
    for (const auto &[mesh, reason] : db.skipped)
        if (k++ < listed)
            std::fprintf(stderr, "occu-preprocess: no skins for %s\n",
                         SkinReport{mesh, scene.meshes[mesh].name, reason}.message().c_str());
    if (db.skipped.size() > listed)
        std::fprintf(stderr, "occu-preprocess: and %zu more meshes without skins (listed in %s)\n",
                     db.skipped.size() - listed, o.out.c_str());
    std::printf("%s: %zu meshes in %.2f s: %zu boxes on %zu meshes, %zu meshes without skins\n", o.out.c_str(),
                db.mesh_count(), s, db.box_count(), db.skins.size(), db.skipped.size());
    // Why meshes have no skins, counted by the kind of reason (the reason
    // up to its first point: "not watertight: the flood from the inner
    // voxel"), and how far the meshes spread: the largest side of each
    // mesh's box over the scene's largest side. A mesh whose box holds the
    // eye cannot stand behind its skins (SkinOccluders::usable), so
    // meshes that span the scene give no usable skins even when they have some.
    std::map<std::string, std::size_t> kinds;
    for (const auto &[mesh, reason] : db.skipped)
        ++kinds[reason.substr(0, reason.find(" at "))];
    for (const auto &[kind, count] : kinds)
        std::printf("  without skins: %zu: %s\n", count, kind.c_str());
    const glm::vec3 scene_extent = scene.bounds.extent();
    const float scene_side = std::max({scene_extent.x, scene_extent.y, scene_extent.z});
    std::vector<float> spread;
    for (std::uint32_t m = 0; m < scene.meshes.size(); ++m)
        if (db.skins.count(m) || db.skipped.count(m)) {
            const glm::vec3 e = scene.meshes[m].bounds.extent();
            spread.push_back(scene_side > 0.0f ? std::max({e.x, e.y, e.z}) / scene_side : 0.0f);
        }
    if (!spread.empty()) {
        std::sort(spread.begin(), spread.end());
        const auto over_half = std::size_t(spread.end() - std::upper_bound(spread.begin(), spread.end(), 0.5f));
        std::printf("  mesh box's largest side / the scene's (%.1f m): median %.0f%%, largest %.0f%%; %zu of %zu "
                    "meshes over half\n",
                    double(scene_side), 100.0 * spread[spread.size() / 2], 100.0 * spread.back(), over_half,
                    spread.size());
    }
    return 0;
}

int view_cells(const Options &o)
{
    using namespace occu;
    if (!o.scene.empty())
        throw std::runtime_error("view-cells needs 2.5D occluders (building footprints with heights, Wonka et al. "
                                 "section 4.1), which only the generated city provides: '" + o.scene +
                                 "' is a loaded scene whose meshes do not say which are solid");
    gl::select_driver(gl::parse_driver(o.driver));
    const SceneSetup setup({"city", o.city_copies, o.leaf_triangles});
    const Scene &scene = setup.scene();
    const Hierarchy &hierarchy = setup.hierarchy();
    const auto cells_start = std::chrono::steady_clock::now();
    const ViewCells cells({scene.bounds.min.x, scene.bounds.min.z}, {scene.bounds.max.x, scene.bounds.max.z},
                          scene.prism_occluders, o.cells);
    const double cells_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - cells_start).count();

    gl::OffscreenContext ctx(64, 64);
    const bool both = o.test == "both";
    const CullMapTest test = o.test == "readback" ? CullMapTest::readback : CullMapTest::occlusion_unit;
    ViewCellVisibility visibility(scene, hierarchy, cells, o.visibility);

    PvsDatabase db = PvsDatabase::start(hierarchy, o.cells, o.visibility);
    for (std::size_t c = 0; c < cells.size(); ++c)
        db.cells.push_back(cells.triangle(c));

    std::vector<std::uint32_t> mine;
    if (o.first_cell >= cells.size())
        throw std::runtime_error("--cells starts at cell " + std::to_string(o.first_cell) + "; there are " +
                                 std::to_string(cells.size()));
    std::vector<bool> on_route(cells.size(), o.route.empty());
    if (!o.route.empty()) {
        for (const Camera &camera : setup.route(o.route, o.route_frames))
            if (const auto c = cells.locate(camera.position))
                on_route[*c] = true;
    }
    for (std::uint32_t c = o.first_cell; c < cells.size() && c <= o.last_cell; ++c)
        if (on_route[c] && int(c % std::uint32_t(o.shards)) == o.shard - 1)
            mine.push_back(c);
    std::printf("scene: %zu triangles, %zu leaves, %zu prism occluders (%zu parts shrunk by %g m); %zu view cells "
                "(edges <= %g m, made in %.2f s), shard %d/%d: %zu cells; cull map pixels %g m; %s\n",
                scene.triangle_count(), hierarchy.leaf_count(), scene.prism_occluders.size(),
                visibility.shrunk_occluders(), o.visibility.epsilon, cells.size(), o.cells.max_edge, cells_s, o.shard,
                o.shards, mine.size(), o.visibility.pixel, ctx.renderer().c_str());

    // Triangles of the leaves, for the share of the scene each set leaves out.
    std::vector<std::uint32_t> leaf_triangles(hierarchy.nodes().size(), 0);
    for (std::uint32_t n = 0; n < hierarchy.nodes().size(); ++n)
        if (hierarchy.nodes()[n].leaf())
            leaf_triangles[n] = hierarchy.nodes()[n].triangle_count;
    struct Sum {
        double ms = 0, map_ms = 0, test_ms = 0, horizon_ms = 0, maps = 0, passes = 0, samples = 0;
    } sum[2];
    double visible_leaves = 0, visible_triangles = 0;
    const auto start = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < mine.size(); ++i) {
        const std::uint32_t c = mine[i];
        std::vector<CellVisibility> results;
        for (CullMapTest t : both ? std::vector<CullMapTest>{CullMapTest::occlusion_unit, CullMapTest::readback}
                                  : std::vector<CullMapTest>{test}) {
            results.push_back(visibility.compute(c, t));
            Sum &s = sum[t == CullMapTest::readback];
            s.map_ms += results.back().map_ms;
            s.test_ms += results.back().test_ms;
            s.horizon_ms += results.back().horizon_ms;
            s.ms += results.back().map_ms + results.back().test_ms;
            s.maps += double(results.back().maps);
            s.passes += double(results.back().unit_passes);
            s.samples += double(results.back().sample_points);
        }
        if (both && results[0].visible_leaves != results[1].visible_leaves)
            throw std::runtime_error("view cell " + std::to_string(c) + ": the Occlusion Unit finds " +
                                     std::to_string(results[0].visible_leaves.size()) +
                                     " visible leaves, the read-back " + std::to_string(results[1].visible_leaves.size()) +
                                     ", and they are not the same");
        db.visible[c] = results[0].visible_leaves;
        visible_leaves += double(results[0].visible_leaves.size());
        for (std::uint32_t n : results[0].visible_leaves)
            visible_triangles += leaf_triangles[n];
        progress("view cells", long(i + 1), long(mine.size()));
    }
    db.save(o.out);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double n = double(std::max<std::size_t>(mine.size(), 1));
    std::printf("%s: %zu cells in %.1f s; per cell %.1f visible leaves of %zu, %.3f%% of the triangles occluded\n",
                o.out.c_str(), mine.size(), s, visible_leaves / n, hierarchy.leaf_count(),
                100.0 * (1.0 - visible_triangles / n / double(scene.triangle_count())));
    for (int k = 0; k < 2; ++k) {
        if (!both && (k == 1) != (test == CullMapTest::readback))
            continue;
        const Sum &m = sum[k];
        std::printf("  %-14s ms per cell %.2f (maps %.2f, object tests %.2f: in the maps %.2f, horizon %.2f); %.2f maps, "
                    "%.1f sample points%s\n",
                    k ? "read-back" : "occlusion-unit", m.ms / n, m.map_ms / n, m.test_ms / n,
                    (m.test_ms - m.horizon_ms) / n, m.horizon_ms / n, m.maps / n, m.samples / n,
                    k ? "" : (", " + std::to_string(m.passes / n) + " brief passes").c_str());
    }
    if (both)
        std::printf("  object tests: read-back %.2fx the Occlusion Unit's time (in the maps alone %.2fx; the horizon is "
                    "the same work both ways); every cell's sets equal\n",
                    sum[1].test_ms / std::max(sum[0].test_ms, 1e-9),
                    (sum[1].test_ms - sum[1].horizon_ms) / std::max(sum[0].test_ms - sum[0].horizon_ms, 1e-9));
    return 0;
}

}  // namespace

int main(int argc, char **argv)
{
    if (argc < 2)
        usage("give a command: build, merge, views, skins or view-cells");
    const std::string command = argv[1];
    if (command == "-h" || command == "--help")
        usage("");
    if (command != "build" && command != "merge" && command != "views" && command != "skins" && command != "view-cells")
        usage("unknown command '" + command + "' (build, merge, views, skins or view-cells)");
    Options o;
    for (int i = 2; i < argc; ++i) {
        const std::string a = argv[i];
        if (a.rfind("--", 0) != 0) {
            if (command == "build" || command == "skins" || command == "view-cells")
                usage("unexpected argument '" + a + "'");
            o.inputs.push_back(a);
            continue;
        }
        if (i + 1 >= argc)
            usage(a + " needs a value");
        const std::string v = argv[++i];
        try {
            if (a == "--out") o.out = v;
            else if (command == "views" && a == "--every") o.every = int(occu::integer_option(a, v, 1, 1 << 20));
            else if (command == "views") usage("views takes only --out, --every and a database, not " + a);
            else if (command == "merge") usage("merge takes only --out and shard files, not " + a);
            else if (command == "skins" && a == "--voxel-size")
                o.skins.voxel_size = float(occu::number_option(a, v, 0.0, 1000.0, true));
            else if (command == "skins" && a == "--max-boxes") o.skins.max_boxes = int(occu::integer_option(a, v, 1, 1 << 20));
            else if (command == "skins" && a == "--min-volume") o.skins.min_volume = float(occu::number_option(a, v, 0.0, 1e12));
            else if (command == "skins" && a == "--start") {
                if (v != "densest" && v != "first")
                    usage("--start wants densest or first, got '" + v + "'");
                o.skins.start = v == "densest" ? occu::SkinOptions::Start::densest : occu::SkinOptions::Start::first;
            }
            else if (command == "skins" && a != "--scene" && a != "--city-copies" && a != "--shard")
                usage("skins takes only --out, --scene, --city-copies, --voxel-size, --max-boxes, --min-volume, "
                      "--start and --shard, not " + a);
            else if (command == "view-cells" && a == "--epsilon") o.visibility.epsilon = occu::number_option(a, v, 0.0, 1e4, true);
            else if (command == "view-cells" && a == "--pixel") o.visibility.pixel = occu::number_option(a, v, 0.0, 1e4, true);
            else if (command == "view-cells" && a == "--initial-extent")
                o.visibility.initial_extent = occu::number_option(a, v, 0.0, 1e6, true);
            else if (command == "view-cells" && a == "--max-edge") o.cells.max_edge = occu::number_option(a, v, 0.0, 1e6, true);
            else if (command == "view-cells" && a == "--cell-top") o.cells.top = occu::number_option(a, v, 0.0, 1e4, true);
            else if (command == "view-cells" && a == "--clearance") o.cells.clearance = occu::number_option(a, v, 0.0, 1e4);
            else if (command == "view-cells" && a == "--route") o.route = v;
            else if (command == "view-cells" && a == "--frames") o.route_frames = int(occu::integer_option(a, v, 1, 1000000));
            else if (command == "view-cells" && a == "--cells") {
                const auto dash = v.find('-');
                if (dash == std::string::npos)
                    usage("--cells wants FIRST-LAST, got '" + v + "'");
                o.first_cell = std::uint32_t(occu::integer_option("--cells FIRST", v.substr(0, dash), 0, 1 << 22));
                o.last_cell = std::uint32_t(occu::integer_option("--cells LAST", v.substr(dash + 1), o.first_cell, 1 << 22));
            }
            else if (command == "view-cells" && a == "--test") {
                if (v != "occlusion-unit" && v != "readback" && v != "both")
                    usage("--test wants occlusion-unit, readback or both, got '" + v + "'");
                o.test = v;
            }
            else if (command == "view-cells" && a != "--scene" && a != "--city-copies" && a != "--shard" &&
                     a != "--driver" && a != "--leaf-triangles")
                usage("view-cells takes only --out, --city-copies, --leaf-triangles, --epsilon, --pixel, --max-edge, "
                      "--cell-top, --clearance, --initial-extent, --test, --cells, --route, --frames, --shard and --driver, not " + a);
            else if (a == "--scene") o.scene = v;
            else if (a == "--driver") o.driver = v;
            else if (a == "--city-copies") o.city_copies = int(occu::integer_option(a, v, 1, 64));
            else if (a == "--leaf-triangles") o.leaf_triangles = occu::leaf_triangles_option(a, v);
            else if (a == "--directions") o.directions = int(occu::integer_option(a, v, 1, 360));
            else if (a == "--max-occluders") o.pre.max_occluders = std::size_t(occu::integer_option(a, v, 1, 1 << 20));
            else if (a == "--pixels-per-occluder")
                o.pre.pixels_per_occluder = occu::number_option(a, v, 1.0, 1e12);
            else if (a == "--selection") {
                if (v != "marginal" && v != "static")
                    usage("--selection wants marginal or static, got '" + v + "'");
                o.pre.marginal_scores = v == "marginal";
            }
            else if (a == "--resolution") o.pre.stacks.resolution = int(occu::integer_option(a, v, 16, 1024));
            else if (a == "--map-divisor") o.pre.stacks.map_divisor = int(occu::integer_option(a, v, 1, 64));
            else if (command == "build" && a == "--cache") o.cache = v;
            else if (a == "--eye-height") o.eye_height = float(occu::number_option(a, v, -1e6, 1e6));
            else if (a == "--grid") {
                std::istringstream in(v);
                char c1 = 0, c2 = 0;
                if (!(in >> o.grid.x >> c1 >> o.grid.y >> c2 >> o.grid.z) || c1 != ',' || c2 != ',' || !in.eof() ||
                    o.grid.x < 1 || o.grid.y < 1 || o.grid.z < 1 || o.grid.x * o.grid.y * o.grid.z > 100000)
                    usage("--grid wants NX,NY,NZ (positive, product at most 100000), got '" + v + "'");
            } else if (a == "--shard") {
                const auto slash = v.find('/');
                if (slash == std::string::npos)
                    usage("--shard wants I/N, got '" + v + "'");
                o.shards = int(occu::integer_option("--shard N", v.substr(slash + 1), 1, 1 << 20));
                o.shard = int(occu::integer_option("--shard I", v.substr(0, slash), 1, o.shards));
            } else
                usage("unknown option '" + a + "'");
        } catch (const std::invalid_argument &e) {
            usage(e.what());
        }
    }
    if (o.out.empty() && (command != "build" || o.cache.empty()))
        usage(command == "build" ? "--out FILE or --cache DIR is required" : "--out FILE is required");
    if (!o.out.empty() && !o.cache.empty())
        usage("give --out FILE or --cache DIR, not both");
    if (command == "merge" && o.inputs.empty())
        usage("merge needs shard files");
    if (command == "views" && o.inputs.size() != 1)
        usage("views needs one database");
    try {
        return command == "merge"        ? merge(o)
               : command == "views"      ? views(o)
               : command == "skins"      ? skins(o)
               : command == "view-cells" ? view_cells(o)
                                         : build(o);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "occu-preprocess: %s\n", e.what());
        return 1;
    }
}
