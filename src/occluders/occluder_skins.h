// SPDX-License-Identifier: MIT
// Occluder skins (Leone, Barbagallo, Banquiero, Agromayor and Bursztyn,
// "Implementing Software Occlusion Culling for Real-Time Applications",
// section 4, after Danell): for each mesh, a few axis-aligned boxes that
// lie inside it and fill as much of it as they can, made offline, so that
// the run time rasterizes a handful of quads per occluder instead of its
// triangles (section 5). Pure geometry: no GL, no Mesa.
//
// Per mesh (occluder_skins), as section 4 lists the steps:
//  1. Voxelize the mesh's bounding box (plus one voxel of padding on every
//     side) and mark "surface voxels": those a triangle overlaps, by a
//     separating-axis triangle/box test after Akenine-Möller (the paper's
//     ref. [12]). A triangle touching a voxel, or passing within a small
//     tolerance of it, counts: inner voxels are strictly clear of the surface.
//  2. A non-surface voxel is a candidate "inner voxel" when it has a surface
//     voxel in each of its six axis directions (the paper's rule, fig. 2).
//     From the first candidate, flood (6-neighbourhood) through non-surface
//     voxels (fig. 3). If the flood reaches the padding the surface leaks:
//     the mesh is not watertight and gets no skins (the paper leaves this
//     open; we detect it) -- unless the candidate was outside all along
//     (winding number 0, step 3: a room whose door is not in line with it
//     sees walls in all six directions). Further candidates outside the
//     regions flooded so far start further floods (several interiors).
//  3. Beyond the paper, each sealed region is confirmed by the winding
//     number of the mesh's triangles at one of its voxels: a region is
//     connected and clear of the surface, so the winding number is the same
//     all over it. Nonzero: inside. Zero: a pocket of outside (a cavity, or
//     a courtyard whose way out is narrower than a voxel) that the flood
//     cannot tell from inside; it is left empty, which keeps skins
//     conservative. Not a whole number: the surface is open (a hole smaller
//     than a voxel), reported as not watertight.
//  4. Boxes one after another: a start voxel (the densest, or the first in
//     scan order, among inner voxels not yet taken), grown by one voxel
//     layer in each of the six directions in turn while the new layer is all
//     inner and not taken, until no direction grows. A box of at least
//     min_volume is kept and its voxels taken; the search stops at
//     max_boxes (the paper's threshold 1) or at the first box below
//     min_volume (threshold 2). The paper searches "in an exhaustive manner"
//     and keeps the largest of the boxes it can grow; here each box grows
//     from one start voxel, the densest by default (the paper's closing
//     suggestion, after Danell): growing from every inner voxel would cost
//     the inner voxels times the growth, for each box.
//
// Conservative: every skin box is a union of inner voxels, each clear of
// every triangle by the tolerance and inside the closed surface (step 3),
// so every box lies inside the mesh. A hole narrower than a voxel is caught
// by step 3, not by the flood.
//
// The skin database (OccluderSkinDatabase) is in occu's database format
// (culling/database_file.h), kind occluder-skins version 1, algorithm
// occluder-skins, made without GL (mesa none); its settings are
// SkinOptions::describe() ("voxel=V max-boxes=N min-volume=M
// start=densest|first"), its scene "FINGERPRINT meshes=M triangles=T"
// (skin_scene_provenance). The payload, by mesh index:
//   skins MESH N X0 Y0 Z0 X1 Y1 Z1 ...    N boxes (min corner, max corner) of mesh MESH
//   skipped MESH REASON                   a mesh without skins, and why
// A shard holds the meshes whose index % N == I - 1
// (occu-preprocess skins --shard I/N); merge() joins shards of one provenance.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "culling/database_file.h"
#include "geometry/aabb.h"
#include "scene/scene.h"

namespace occu {

struct SkinOptions {
    // Edge of a voxel, metres. 0.5 for the default city: its buildings are
    // 12 to 15 m wide and 13 to 54 m high, so the surface voxels cost each
    // side less than a voxel (measured: a skin holds 83 to 93 % of its
    // building's body, 89 % in all), a building's grid has at most
    // 34 x 112 x 34 voxels, and the city's 589 meshes take about a second.
    // 0.25 m takes seven times as long for 95 % (and the ground's grid is
    // too large); 1 m, a sixth of the time for 86 % (67 % for the smallest
    // building, and the ground, 1 m thick, has no interior). The ledges,
    // 0.25 m thick, stay out of the skins at either size.
    float voxel_size = 0.5f;
    // Threshold 1 of section 4: boxes per mesh, at least 1.
    int max_boxes = 8;
    // Threshold 2 of section 4, m^3: the first box below it is dropped and
    // ends the mesh's search. 1 m^3 keeps boxes of 8 voxels and more at the
    // default voxel size: smaller ones hide next to nothing.
    float min_volume = 1.0f;
    // Where each box starts growing. densest: Danell's "densest" inner
    // voxel, here the one farthest (chessboard distance) from the nearest
    // voxel that is not free (surface, outside or taken), ties to the first
    // in scan order; not the paper's largest mean distance to all surface
    // voxels, which costs inner x surface voxels (about 10^9 per building)
    // and measures mass rather than room: the chessboard distance is the
    // half-size of the largest free cube centred at the voxel, the best seed
    // for a box grown layer by layer, and two raster passes compute it for
    // all voxels. first: the first free inner voxel in scan order (x fastest,
    // then y, then z), as the paper's text takes "another initial inner voxel".
    enum class Start { densest, first };
    Start start = Start::densest;

    // "voxel=0.5 max-boxes=8 min-volume=1 start=densest": the options as
    // a database's provenance records them.
    std::string describe() const;
    // Why these options cannot be used (voxel size not positive and finite,
    // max_boxes < 1, min_volume negative or not finite); empty when they can.
    std::string problem() const;
};

// A voxel grid larger than this is not made (the mesh is reported, naming a
// voxel size that would do): about 32 M voxels, some 100 MB of work arrays.
constexpr std::size_t max_skin_voxels = std::size_t(1) << 25;

// The skins of one mesh, in the order found. std::nullopt
// (with `why` filled) when the mesh has no skins to give: see-through
// (Mesh::occluder false: it hides nothing behind it), not watertight,
// no interior at this voxel size (thinner than about two voxels), grid too
// large, no triangles, or bad vertices or indices. A watertight mesh whose
// first box is below min_volume gives an empty vector. Throws
// std::invalid_argument when options.problem() is not empty.
std::optional<std::vector<Aabb>> occluder_skins(const Mesh &mesh, const SkinOptions &options,
                                                std::string *why = nullptr);

struct MeshSkins {
    std::uint32_t mesh = 0;   // index into Scene::meshes
    std::vector<Aabb> boxes;
};

// A mesh without skins.
struct SkinReport {
    std::uint32_t mesh = 0;
    std::string name;      // Mesh::name, empty when the mesh has none
    std::string problem;   // occluder_skins' why
    // "mesh 12 'ground': not watertight: ..." (or "mesh 12 (unnamed): ...").
    std::string message() const;
};

struct SceneSkins {
    std::vector<MeshSkins> skins;      // meshes with skins (possibly none), by mesh index
    std::vector<SkinReport> skipped;   // meshes without, by mesh index
    std::size_t box_count() const;
};

// The skins of a whole scene in memory, for programs that want no file:
// the meshes m with m % shards == shard - 1 (all of them by default).
// `progress`, when given, is called after each mesh with (done, total).
SceneSkins scene_skins(const Scene &scene, const SkinOptions &options, int shard = 1, int shards = 1,
                       const std::function<void(std::size_t, std::size_t)> &progress = {});

// A hash of the scene's meshes (their vertex positions and indices, in
// order): what a skin database was made for. 16 hex digits.
std::string scene_geometry_fingerprint(const Scene &scene);

// What a skin database was made for: "FINGERPRINT meshes=M triangles=T",
// the scene's geometry fingerprint and counts.
std::string skin_scene_provenance(const Scene &scene);

class OccluderSkinDatabase {
public:
    DatabaseProvenance provenance;
    std::uint32_t meshes = 0;                           // the scene's (its provenance's meshes=)
    std::map<std::uint32_t, std::vector<Aabb>> skins;   // mesh -> its boxes
    std::map<std::uint32_t, std::string> skipped;       // mesh -> why it has none

    // The provenance of a database of `scene`'s skins made here with `options`.
    static DatabaseProvenance provenance_for(const Scene &scene, const SkinOptions &options);
    // Skins of the meshes of shard I of N (see scene_skins) of `scene`.
    static OccluderSkinDatabase make(const Scene &scene, const SkinOptions &options, int shard = 1, int shards = 1,
                                     const std::function<void(std::size_t, std::size_t)> &progress = {});

    // The boxes of `mesh`; empty when it has none or is not in the database.
    const std::vector<Aabb> &boxes(std::uint32_t mesh) const;
    std::size_t box_count() const;
    // Meshes with a skins or skipped line.
    std::size_t mesh_count() const { return skins.size() + skipped.size(); }

    void save(const std::string &path) const;
    // Throws std::runtime_error naming the file and the line of what is
    // wrong (a coordinate that is not a finite float among it), or another
    // algorithm's database.
    static OccluderSkinDatabase load(const std::string &path);
    // Joins shards. Throws std::runtime_error when their provenance differs
    // (naming the difference) or a mesh is in more than one; `names`, when
    // given, names the shards in messages (else "shard 2").
    static OccluderSkinDatabase merge(const std::vector<OccluderSkinDatabase> &shards,
                                      const std::vector<std::string> &names = {});
    bool operator==(const OccluderSkinDatabase &o) const;
};

}  // namespace occu
