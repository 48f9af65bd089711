// SPDX-License-Identifier: MIT
// The potentially visible sets of a scene's view cells (Wonka, Wimmer and
// Schmalstieg 2000, section 7.3: "object IDs of potentially visible objects
// for each view cell"), in occu's database format (culling/database_file.h):
// kind pvs version 1, algorithm view-cells, made with the Mesa whose
// Occlusion Unit (or read-back) tested the cull maps. Its settings
//   epsilon=E pixel=K initial-extent=X max-edge=M clearance=C close-gaps=G bottom=B top=T
// say how the cells and their sets were made, its scene the hierarchy whose
// leaves the sets name (scene_provenance), so a database never serves
// another scene, hierarchy or setting. The payload: the cells' triangles
// (every file has them all, so a shard alone can locate an eye) and, per
// cell made, its visible leaves:
//   cells N
//   cell I X0 Z0 X1 Z1 X2 Z2             N lines, I = 0 .. N - 1 (metres)
//   pvs I COUNT LEAF...                   one per cell made, ascending leaves
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "culling/database_file.h"
#include "strategies/wonka_view_cells/view_cell_visibility.h"
#include "strategies/wonka_view_cells/view_cells.h"

namespace occu {

class PvsDatabase {
public:
    DatabaseProvenance provenance;
    // Of its settings: how the cells and their sets were made.
    ViewCellOptions cell_options;
    ViewCellVisibilityOptions visibility_options;
    std::vector<std::array<glm::dvec2, 3>> cells;
    std::map<std::uint32_t, std::vector<std::uint32_t>> visible;   // cell -> its visible leaves

    // A database to be made here for `hierarchy` with these options: its
    // provenance and options, no cells yet.
    static PvsDatabase start(const Hierarchy &hierarchy, const ViewCellOptions &cells,
                             const ViewCellVisibilityOptions &visibility);

    // The cells of `scene`'s ground (its 2.5D occluders', view_cells.h)
    // and every cell's set, found with `test` (view_cell_visibility.h;
    // needs what that needs).
    static PvsDatabase make(const Scene &scene, const Hierarchy &hierarchy, const ViewCellOptions &cells,
                            const ViewCellVisibilityOptions &visibility, CullMapTest test);

    void save(const std::string &path) const;
    // Throws std::runtime_error naming the file and line of what is wrong,
    // or another algorithm's database.
    static PvsDatabase load(const std::string &path);
    // Joins shards made with one provenance and cells; throws
    // std::runtime_error naming the difference, or a cell in two shards.
    static PvsDatabase merge(const std::vector<PvsDatabase> &shards, const std::vector<std::string> &names = {});
    bool operator==(const PvsDatabase &o) const;
};

}  // namespace occu
