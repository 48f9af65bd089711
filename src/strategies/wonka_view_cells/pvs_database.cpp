// SPDX-License-Identifier: MIT
#include "strategies/wonka_view_cells/pvs_database.h"

#include <cmath>
#include <stdexcept>

namespace occu {

PvsDatabase PvsDatabase::start(const Hierarchy &hierarchy, const ViewCellOptions &cells,
                               const ViewCellVisibilityOptions &visibility)
{
    PvsDatabase db;
    db.cell_options = cells;
    db.visibility_options = visibility;
    const std::pair<const char *, double> settings[] = {
        {"epsilon", visibility.epsilon},  {"pixel", visibility.pixel},           {"initial-extent", visibility.initial_extent},
        {"max-edge", cells.max_edge},     {"clearance", cells.clearance},        {"close-gaps", cells.close_gaps},
        {"bottom", cells.bottom},         {"top", cells.top}};
    std::string text;
    for (const auto &[key, value] : settings)
        text += std::string(text.empty() ? "" : " ") + key + "=" + exact_number(value);
    // The cull maps are drawn, and tested, with GL.
    db.provenance = DatabaseProvenance::current("view-cells", text, scene_provenance(hierarchy), true);
    return db;
}

PvsDatabase PvsDatabase::make(const Scene &scene, const Hierarchy &hierarchy, const ViewCellOptions &options,
                              const ViewCellVisibilityOptions &visibility_options, CullMapTest test)
{
    const ViewCells cells({scene.bounds.min.x, scene.bounds.min.z}, {scene.bounds.max.x, scene.bounds.max.z},
                          scene.prism_occluders, options);
    ViewCellVisibility visibility(scene, hierarchy, cells, visibility_options);
    PvsDatabase db = start(hierarchy, options, visibility_options);
    for (std::uint32_t c = 0; c < cells.size(); ++c) {
        db.cells.push_back(cells.triangle(c));
        db.visible[c] = visibility.compute(c, test).visible_leaves;
    }
    return db;
}

void PvsDatabase::save(const std::string &path) const
{
    DatabaseWriter writer(path, "pvs", 1, provenance);
    std::ostream &out = writer.out();
    out << "cells " << cells.size() << '\n';
    for (std::size_t i = 0; i < cells.size(); ++i) {
        out << "cell " << i;
        for (const glm::dvec2 &p : cells[i])
            out << ' ' << exact_number(p.x) << ' ' << exact_number(p.y);
        out << '\n';
    }
    for (const auto &[cell, leaves] : visible) {
        out << "pvs " << cell << ' ' << leaves.size();
        for (std::uint32_t l : leaves)
            out << ' ' << l;
        out << '\n';
    }
    writer.finish();
}

PvsDatabase PvsDatabase::load(const std::string &path)
{
    DatabaseReader in(path, "pvs", 1, "PVS database");
    in.require_algorithm("view-cells");
    PvsDatabase db;
    db.provenance = in.provenance();
    ViewCellVisibilityOptions &v = db.visibility_options;
    ViewCellOptions &c = db.cell_options;
    v.epsilon = in.setting("epsilon", 0.0, 1e6);
    v.pixel = in.setting("pixel", 0.0, 1e6);
    v.initial_extent = in.setting("initial-extent", 0.0, 1e9);
    c.max_edge = in.setting("max-edge", 0.0, 1e9);
    c.clearance = in.setting("clearance", 0.0, 1e6);
    c.close_gaps = in.setting("close-gaps", 0.0, 1e6);
    c.bottom = in.setting("bottom", -1e9, 1e9);
    c.top = in.setting("top", -1e9, 1e9);
    if (!(c.bottom < c.top))
        in.fail_at(in.settings_line(), "settings: bottom is not below top");

    if (!in.next() || in.record() != "cells")
        in.fail("want 'cells N' first");
    const std::size_t n = std::size_t(in.count("the number of cells", 1u << 22));
    in.done();
    if (n == 0)
        in.fail("no cells");
    db.cells.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        if (!in.next() || in.record() != "cell")
            in.fail("want 'cell I X0 Z0 X1 Z1 X2 Z2' (cell " + std::to_string(i) + " of " + std::to_string(n) + ")");
        if (const std::uint64_t number = in.count("the cell's number", n); number != i)
            in.fail("cell " + std::to_string(number) + " where cell " + std::to_string(i) + " belongs");
        for (glm::dvec2 &p : db.cells[i]) {
            p = {in.number("x"), in.number("z")};
            if (std::abs(p.x) > 1e9 || std::abs(p.y) > 1e9)
                in.fail("a corner beyond 1e9 m of the origin");
        }
        in.done();
        const auto &t = db.cells[i];
        if ((t[1].x - t[0].x) * (t[2].y - t[0].y) - (t[1].y - t[0].y) * (t[2].x - t[0].x) == 0.0)
            in.fail("cell " + std::to_string(i) + " has no area");
    }
    while (in.next()) {
        if (in.record() != "pvs")
            in.fail("want 'pvs I COUNT LEAF...' or 'end', got '" + in.record() + "'");
        const std::uint32_t cell = std::uint32_t(in.count("the cell", n - 1));
        const std::uint64_t k = in.count("the number of leaves", 0xFFFFFFFFu);
        if (db.visible.count(cell))
            in.fail("cell " + std::to_string(cell) + " again");
        std::vector<std::uint32_t> &leaves = db.visible[cell];
        for (std::uint64_t i = 0; i < k; ++i) {
            if (!in.more())
                in.fail("says " + std::to_string(k) + " leaves and lists " + std::to_string(i));
            leaves.push_back(std::uint32_t(in.count("a leaf", 0xFFFFFFFFu)));
            if (i > 0 && leaves[i] <= leaves[i - 1])
                in.fail("leaves not ascending");
        }
        if (in.more())
            in.fail("says " + std::to_string(k) + " leaves and lists more");
    }
    return db;
}

PvsDatabase PvsDatabase::merge(const std::vector<PvsDatabase> &shards, const std::vector<std::string> &names)
{
    if (shards.empty())
        throw std::runtime_error("no shards to merge");
    auto name = [&](std::size_t i) { return i < names.size() ? names[i] : "shard " + std::to_string(i + 1); };
    PvsDatabase out = shards[0];
    out.visible.clear();
    for (std::size_t i = 0; i < shards.size(); ++i) {
        const std::string d = shards[i].provenance.difference(out.provenance);
        if (!d.empty())
            throw std::runtime_error(name(i) + " was made otherwise than " + name(0) + ": " + d);
        if (shards[i].cells != out.cells)
            throw std::runtime_error(name(i) + " has other view cells than " + name(0));
        for (const auto &[cell, leaves] : shards[i].visible)
            if (!out.visible.emplace(cell, leaves).second)
                throw std::runtime_error("cell " + std::to_string(cell) + " is in " + name(i) + " and an earlier shard");
    }
    return out;
}

bool PvsDatabase::operator==(const PvsDatabase &o) const
{
    return provenance == o.provenance && cells == o.cells && visible == o.visible;
}

}  // namespace occu
