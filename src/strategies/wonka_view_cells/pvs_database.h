// The potentially visible sets of a scene's view cells (Wonka, Wimmer and
// Schmalstieg 2000, section 7.3: "object IDs of potentially visible objects
// for each view cell"), as a text file: the cells' triangles (every file
// has them all, so a shard alone can locate an eye) and, per cell made, its
// visible leaves. Provenance says what it was made from and with, so a
// database never serves another scene, hierarchy or setting.
//
//   occu-pvs-database 1
//   hierarchy FINGERPRINT LEAVES        Hierarchy::fingerprint(), its leaf count
//   options epsilon=E pixel=K max-edge=M clearance=C bottom=B top=T initial-extent=X
//   cells N
//   cell I X0 Z0 X1 Z1 X2 Z2             N lines, I = 0 .. N - 1 (metres, %.17g)
//   pvs I COUNT LEAF...                   one per cell made, ascending leaves
//   end
//
// Errors name the file and the line.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "strategies/wonka_view_cells/view_cell_visibility.h"
#include "strategies/wonka_view_cells/view_cells.h"

namespace occu {

struct PvsProvenance {
    std::string hierarchy;        // Hierarchy::fingerprint()
    std::uint64_t leaves = 0;     // leaves of that hierarchy
    double epsilon = 0, pixel = 0, max_edge = 0, clearance = 0, bottom = 0, top = 0, initial_extent = 0;

    // For a database about to be made here.
    static PvsProvenance current(const Hierarchy &hierarchy, const ViewCellOptions &cells,
                                 const ViewCellVisibilityOptions &visibility);
    std::string describe_options() const;
    // The first field that differs, both values named; empty when none does.
    std::string difference(const PvsProvenance &other) const;
};

class PvsDatabase {
public:
    PvsProvenance provenance;
    std::vector<std::array<glm::dvec2, 3>> cells;
    std::map<std::uint32_t, std::vector<std::uint32_t>> visible;   // cell -> its visible leaves

    ViewCellOptions cell_options() const;

    // The cells of `scene`'s ground (its 2.5D occluders', view_cells.h)
    // and every cell's set, found with `test` (view_cell_visibility.h;
    // needs what that needs).
    static PvsDatabase make(const Scene &scene, const Hierarchy &hierarchy, const ViewCellOptions &cells,
                            const ViewCellVisibilityOptions &visibility, CullMapTest test);

    void save(const std::string &path) const;
    // Throws std::runtime_error naming the file and line of what is wrong.
    static PvsDatabase load(const std::string &path);
    // Joins shards made with one provenance and cells; throws
    // std::runtime_error naming the difference, or a cell in two shards.
    static PvsDatabase merge(const std::vector<PvsDatabase> &shards, const std::vector<std::string> &names = {});
    bool operator==(const PvsDatabase &o) const;
};

}  // namespace occu
