// SPDX-License-Identifier: MIT
// The one resource provider: the databases a strategy reads
// (StrategyFamily::databases) that its settings do not name are made here
// on demand, or found where an earlier run made them, by their full
// provenance (culling/database_file.h): what the family says its contents
// depend on (algorithm, settings, scene and hierarchy), this library's code
// (a hash the build computes over every source of src/) and the Mesa build.
// A database is kept in the provider's directory under a name of that
// provenance's key, written whole before it is named, so that processes
// sharing the directory never read half a database. One found there is
// read through: when its provenance is not the one asked for (a key shared
// by chance) or it does not read as a database (cut short, its provenance
// damaged, or of a format this program does not read), it is made again,
// and the report says why.
// The strategy's own reader then checks what it can (the scene it was made
// for), naming the file and line of what is wrong.
#pragma once

#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "culling/registry.h"

namespace occu {

// The databases `choice` reads (of its family's, those its settings read),
// given or not.
std::vector<const DatabaseNeed *> databases_read(const StrategyChoice &choice);

class DatabaseProvider {
public:
    // Which databases it makes when a strategy was not given one: those
    // the strategy requires, or also those it would make itself during
    // the run (which benchmarks want made beforehand, out of the figures).
    enum class Makes { required, all };

    // Databases are kept in `directory` (made when missing). What it made,
    // and how long that took, is said on `report` (null: nowhere).
    explicit DatabaseProvider(std::string directory, Makes makes = Makes::required, std::FILE *report = stdout);

    // The settings ("setting=FILE") that give `choice` each database it
    // reads, its settings do not name and this provider makes, for
    // `context`'s scene and frames of width x height: made here the first
    // time (restoring the GL state the making changes), found in the
    // directory afterwards. Throws what making one throws (and
    // std::runtime_error naming the directory when it cannot write there).
    std::vector<std::string> settings_for(const StrategyChoice &choice, const StrategyContext &context, int width,
                                          int height);

    const std::string &directory() const { return directory_; }
    // The databases made by this provider (not found, or found and made
    // again): their paths.
    const std::vector<std::string> &made() const { return made_; }

private:
    std::string directory_;
    Makes makes_;
    std::FILE *report_;
    std::vector<std::string> made_;
};

// A program's --make-databases: "required" or "all"; throws
// std::invalid_argument naming `option` and what it got otherwise.
DatabaseProvider::Makes make_databases_option(const std::string &option, const std::string &text);

// The directory programs keep databases in unless told otherwise:
// $XDG_CACHE_HOME/occu/databases, or ~/.cache/occu/databases.
std::string default_database_directory();

}  // namespace occu
