#include "strategies/wonka_view_cells/pvs_database.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace occu {

namespace {

std::string number(double v)
{
    char buf[40];
    std::snprintf(buf, sizeof(buf), "%.17g", v);
    return buf;
}

[[noreturn]] void fail(const std::string &path, std::size_t line, const std::string &what)
{
    throw std::runtime_error(path + ":" + std::to_string(line) + ": " + what);
}

double finite_number(const std::string &path, std::size_t line, const std::string &word, const char *what)
{
    char *end = nullptr;
    const double v = std::strtod(word.c_str(), &end);
    if (word.empty() || *end != '\0' || !std::isfinite(v))
        fail(path, line, std::string(what) + " is '" + word + "', not a finite number");
    return v;
}

std::uint64_t count(const std::string &path, std::size_t line, const std::string &word, const char *what,
                    std::uint64_t max)
{
    if (word.empty() || word.find_first_not_of("0123456789") != std::string::npos || word.size() > 19)
        fail(path, line, std::string(what) + " is '" + word + "', not a count");
    const std::uint64_t v = std::stoull(word);
    if (v > max)
        fail(path, line, std::string(what) + " " + word + " is more than " + std::to_string(max));
    return v;
}

}  // namespace

std::string PvsProvenance::describe_options() const
{
    return "epsilon=" + number(epsilon) + " pixel=" + number(pixel) + " max-edge=" + number(max_edge) + " clearance=" + number(clearance) +
           " bottom=" + number(bottom) + " top=" + number(top) + " initial-extent=" + number(initial_extent);
}

std::string PvsProvenance::difference(const PvsProvenance &o) const
{
    if (hierarchy != o.hierarchy)
        return "hierarchy '" + hierarchy + "' against '" + o.hierarchy + "'";
    if (leaves != o.leaves)
        return "leaves " + std::to_string(leaves) + " against " + std::to_string(o.leaves);
    if (describe_options() != o.describe_options())
        return "options '" + describe_options() + "' against '" + o.describe_options() + "'";
    return "";
}

PvsProvenance PvsProvenance::current(const Hierarchy &hierarchy, const ViewCellOptions &cells,
                                     const ViewCellVisibilityOptions &visibility)
{
    PvsProvenance p;
    p.hierarchy = hierarchy.fingerprint();
    p.leaves = hierarchy.leaf_count();
    p.epsilon = visibility.epsilon;
    p.pixel = visibility.pixel;
    p.initial_extent = visibility.initial_extent;
    p.max_edge = cells.max_edge;
    p.clearance = cells.clearance;
    p.bottom = cells.bottom;
    p.top = cells.top;
    return p;
}

PvsDatabase PvsDatabase::make(const Scene &scene, const Hierarchy &hierarchy, const ViewCellOptions &options,
                              const ViewCellVisibilityOptions &visibility_options, CullMapTest test)
{
    const ViewCells cells({scene.bounds.min.x, scene.bounds.min.z}, {scene.bounds.max.x, scene.bounds.max.z},
                          scene.prism_occluders, options);
    ViewCellVisibility visibility(scene, hierarchy, cells, visibility_options);
    PvsDatabase db;
    db.provenance = PvsProvenance::current(hierarchy, options, visibility_options);
    for (std::uint32_t c = 0; c < cells.size(); ++c) {
        db.cells.push_back(cells.triangle(c));
        db.visible[c] = visibility.compute(c, test).visible_leaves;
    }
    return db;
}

ViewCellOptions PvsDatabase::cell_options() const
{
    ViewCellOptions c;
    c.max_edge = provenance.max_edge;
    c.clearance = provenance.clearance;
    c.bottom = provenance.bottom;
    c.top = provenance.top;
    return c;
}

void PvsDatabase::save(const std::string &path) const
{
    std::ofstream out(path);
    if (!out)
        throw std::runtime_error(path + ": cannot write");
    out << "occu-pvs-database 1\n";
    out << "hierarchy " << provenance.hierarchy << ' ' << provenance.leaves << '\n';
    out << "options " << provenance.describe_options() << '\n';
    out << "cells " << cells.size() << '\n';
    for (std::size_t i = 0; i < cells.size(); ++i) {
        out << "cell " << i;
        for (const glm::dvec2 &p : cells[i])
            out << ' ' << number(p.x) << ' ' << number(p.y);
        out << '\n';
    }
    for (const auto &[cell, leaves] : visible) {
        out << "pvs " << cell << ' ' << leaves.size();
        for (std::uint32_t l : leaves)
            out << ' ' << l;
        out << '\n';
    }
    out << "end\n";
    if (!out.flush())
        throw std::runtime_error(path + ": write failed");
}

PvsDatabase PvsDatabase::load(const std::string &path)
{
    std::ifstream in(path);
    if (!in)
        throw std::runtime_error(path + ": cannot read");
    PvsDatabase db;
    std::string text;
    std::size_t line = 0;
    auto next = [&](const char *expected) {
        if (!std::getline(in, text))
            fail(path, line + 1, std::string("ends before its ") + expected + " line");
        ++line;
        std::istringstream words(text);
        std::vector<std::string> w;
        for (std::string s; words >> s;)
            w.push_back(s);
        return w;
    };
    std::vector<std::string> w = next("first");
    if (w.size() != 2 || w[0] != "occu-pvs-database" || w[1] != "1")
        fail(path, line, "not an occu PVS database (want 'occu-pvs-database 1')");
    w = next("hierarchy");
    if (w.size() != 3 || w[0] != "hierarchy")
        fail(path, line, "want 'hierarchy FINGERPRINT LEAVES'");
    db.provenance.hierarchy = w[1];
    db.provenance.leaves = count(path, line, w[2], "leaves", 1ull << 32);
    w = next("options");
    if (w.size() != 8 || w[0] != "options")
        fail(path, line, "want 'options epsilon=E pixel=K max-edge=M clearance=C bottom=B top=T initial-extent=X'");
    const char *keys[] = {"epsilon", "pixel", "max-edge", "clearance", "bottom", "top", "initial-extent"};
    double *fields[] = {&db.provenance.epsilon, &db.provenance.pixel, &db.provenance.max_edge, &db.provenance.clearance,
                        &db.provenance.bottom, &db.provenance.top, &db.provenance.initial_extent};
    for (int i = 0; i < 7; ++i) {
        const std::string prefix = std::string(keys[i]) + "=";
        if (w[std::size_t(i + 1)].rfind(prefix, 0) != 0)
            fail(path, line, "option " + std::to_string(i + 1) + " is '" + w[std::size_t(i + 1)] + "', want " + prefix + "...");
        *fields[i] = finite_number(path, line, w[std::size_t(i + 1)].substr(prefix.size()), keys[i]);
    }
    if (!(db.provenance.bottom < db.provenance.top))
        fail(path, line, "bottom is not below top");
    if (db.provenance.clearance < 0.0)
        fail(path, line, "the clearance is negative");
    w = next("cells");
    if (w.size() != 2 || w[0] != "cells")
        fail(path, line, "want 'cells N'");
    const std::size_t n = std::size_t(count(path, line, w[1], "cells", 1u << 22));
    if (n == 0)
        fail(path, line, "no cells");
    db.cells.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        w = next("cell");
        if (w.size() != 8 || w[0] != "cell")
            fail(path, line, "want 'cell I X0 Z0 X1 Z1 X2 Z2'");
        if (count(path, line, w[1], "cell number", n) != i)
            fail(path, line, "cell " + w[1] + " where cell " + std::to_string(i) + " belongs");
        for (int c = 0; c < 3; ++c) {
            db.cells[i][std::size_t(c)] = {finite_number(path, line, w[std::size_t(2 + 2 * c)], "x"),
                                           finite_number(path, line, w[std::size_t(3 + 2 * c)], "z")};
            const glm::dvec2 &p = db.cells[i][std::size_t(c)];
            if (std::abs(p.x) > 1e9 || std::abs(p.y) > 1e9)
                fail(path, line, "a corner beyond 1e9 m of the origin");
        }
        const auto &t = db.cells[i];
        if ((t[1].x - t[0].x) * (t[2].y - t[0].y) - (t[1].y - t[0].y) * (t[2].x - t[0].x) == 0.0)
            fail(path, line, "cell " + std::to_string(i) + " has no area");
    }
    for (;;) {
        w = next("pvs or end");
        if (w.size() == 1 && w[0] == "end")
            break;
        if (w.size() < 3 || w[0] != "pvs")
            fail(path, line, "want 'pvs I COUNT LEAF...' or 'end'");
        const std::uint32_t cell = std::uint32_t(count(path, line, w[1], "cell", n - 1));
        const std::size_t k = std::size_t(count(path, line, w[2], "count", 1u << 31));
        if (w.size() != 3 + k)
            fail(path, line, "says " + std::to_string(k) + " leaves and lists " + std::to_string(w.size() - 3));
        if (db.visible.count(cell))
            fail(path, line, "cell " + std::to_string(cell) + " again");
        std::vector<std::uint32_t> &leaves = db.visible[cell];
        for (std::size_t i = 0; i < k; ++i) {
            leaves.push_back(std::uint32_t(count(path, line, w[3 + i], "leaf", 0xFFFFFFFFu)));
            if (i > 0 && leaves[i] <= leaves[i - 1])
                fail(path, line, "leaves not ascending");
        }
    }
    return db;
}

PvsDatabase PvsDatabase::merge(const std::vector<PvsDatabase> &shards, const std::vector<std::string> &names)
{
    if (shards.empty())
        throw std::runtime_error("no shards to merge");
    auto name = [&](std::size_t i) { return i < names.size() ? names[i] : "shard " + std::to_string(i + 1); };
    PvsDatabase out;
    out.provenance = shards[0].provenance;
    out.cells = shards[0].cells;
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
    return provenance.difference(o.provenance).empty() && cells == o.cells && visible == o.visible;
}

}  // namespace occu
