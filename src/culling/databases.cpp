// SPDX-License-Identifier: MIT
#include "culling/databases.h"

#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "gl/gl_headers.h"

namespace occu {

namespace {

// Why the file at `path` is not a whole database of `provenance`; empty
// when it is one.
std::string not_the_database(const std::string &path, const DatabaseProvenance &provenance)
{
    try {
        DatabaseReader reader(path, "", 0, "database");
        if (const std::string d = reader.provenance().difference(provenance); !d.empty())
            return "its provenance differs: " + d;
        while (reader.next()) {
        }
    } catch (const std::runtime_error &e) {
        return e.what();
    }
    return {};
}

}  // namespace

std::vector<const DatabaseNeed *> databases_read(const StrategyChoice &choice)
{
    std::vector<const DatabaseNeed *> read;
    for (const DatabaseNeed &d : choice.family->databases)
        if (d.read_by_settings(choice.settings))
            read.push_back(&d);
    return read;
}

DatabaseProvider::DatabaseProvider(std::string directory, Makes makes, std::FILE *report)
    : directory_(std::move(directory)), makes_(makes), report_(report)
{
}

std::vector<std::string> DatabaseProvider::settings_for(const StrategyChoice &choice, const StrategyContext &context,
                                                        int width, int height)
{
    std::vector<std::string> settings;
    for (const DatabaseNeed *need : databases_read(choice)) {
        if (!choice.settings.text(need->setting).empty() || (!need->required && makes_ == Makes::required))
            continue;
        const DatabaseRequest request{context, choice.settings, width, height};
        const DatabaseProvenance provenance = need->provenance(request);
        const std::string path = directory_ + "/" + need->setting + "-" + provenance.key() + ".db";
        std::error_code error;
        const bool found = std::filesystem::exists(path, error);
        const std::string unfit = found ? not_the_database(path, provenance) : "";
        if (!found || !unfit.empty()) {
            std::filesystem::create_directories(directory_, error);
            if (error)
                throw std::runtime_error("cannot make the database directory '" + directory_ + "': " + error.message());
            // Written whole under a name of this process's, then named.
            const std::string part = path + ".part-" + std::to_string(getpid());
            const auto start = std::chrono::steady_clock::now();
            // The making draws with its own state (framebuffers, viewports).
            glPushAttrib(GL_ALL_ATTRIB_BITS);
            try {
                need->make(request, part);
                // What was made must be what was asked for, or every run
                // would make it again.
                if (const std::string why = not_the_database(part, provenance); !why.empty())
                    throw std::logic_error(need->name + " made for " + choice.label() + " is not the one asked for: " +
                                           why);
            } catch (...) {
                glPopAttrib();
                std::filesystem::remove(part, error);
                throw;
            }
            glPopAttrib();
            std::filesystem::rename(part, path, error);
            if (error)
                throw std::runtime_error("cannot name the database '" + path + "': " + error.message());
            made_.push_back(path);
            if (report_ && !unfit.empty())
                std::fprintf(report_, "%s made again: %s\n", path.c_str(), unfit.c_str());
            if (report_)
                std::fprintf(report_, "%s made (for %s) in %.1f s: %s\n", need->name.c_str(), choice.label().c_str(),
                             std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                             path.c_str());
        }
        settings.push_back(need->setting + "=" + path);
    }
    return settings;
}

DatabaseProvider::Makes make_databases_option(const std::string &option, const std::string &text)
{
    if (text == "required")
        return DatabaseProvider::Makes::required;
    if (text == "all")
        return DatabaseProvider::Makes::all;
    throw std::invalid_argument(option + " wants required or all, got '" + text + "'");
}

std::string default_database_directory()
{
    if (const char *cache = std::getenv("XDG_CACHE_HOME"); cache && *cache)
        return std::string(cache) + "/occu/databases";
    if (const char *home = std::getenv("HOME"); home && *home)
        return std::string(home) + "/.cache/occu/databases";
    return "occu-databases";
}

}  // namespace occu
