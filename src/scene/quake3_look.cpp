// SPDX-License-Identifier: MIT
#include "scene/quake3_look.h"

#include <stb/stb_image.h>
#include <zip.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>

namespace occu {

namespace {

std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

struct ArchiveCloser {
    void operator()(zip_t *z) const { zip_discard(z); }
};
struct FileCloser {
    void operator()(zip_file_t *f) const { zip_fclose(f); }
};

// The files of every pk3 in one directory, later pk3s (by name) first.
class SearchPath {
public:
    explicit SearchPath(const std::filesystem::path &directory)
    {
        std::vector<std::filesystem::path> paks;
        std::error_code error;
        for (const auto &entry : std::filesystem::directory_iterator(directory, error))
            if (lower(entry.path().extension().string()) == ".pk3")
                paks.push_back(entry.path());
        if (error)
            throw std::runtime_error("cannot list the level's directory '" + directory.string() + "': " + error.message());
        std::sort(paks.begin(), paks.end());
        for (const auto &pak : paks) {
            int code = 0;
            zip_t *z = zip_open(pak.c_str(), ZIP_RDONLY, &code);
            if (!z)
                throw std::runtime_error("cannot open the pk3 '" + pak.string() + "' for the level's pictures");
            archives_.emplace_back(z);
            const zip_int64_t n = zip_get_num_entries(z, 0);
            for (zip_int64_t i = 0; i < n; ++i)
                if (const char *name = zip_get_name(z, zip_uint64_t(i), 0))
                    files_[lower(name)] = {archives_.size() - 1, zip_uint64_t(i)};
        }
    }

    bool has(const std::string &name) const { return files_.count(lower(name)) > 0; }

    // The bytes of `name`; empty when it is not there or cannot be read.
    std::vector<char> read(const std::string &name) const
    {
        const auto it = files_.find(lower(name));
        if (it == files_.end())
            return {};
        zip_t *z = archives_[it->second.first].get();
        zip_stat_t stat;
        zip_stat_init(&stat);
        if (zip_stat_index(z, it->second.second, 0, &stat) != 0 || !(stat.valid & ZIP_STAT_SIZE) ||
            stat.size > (std::uint64_t(1) << 28))
            return {};
        std::unique_ptr<zip_file_t, FileCloser> file(zip_fopen_index(z, it->second.second, 0));
        if (!file)
            return {};
        std::vector<char> bytes(std::size_t(stat.size));
        std::size_t got = 0;
        while (got < bytes.size()) {
            const zip_int64_t n = zip_fread(file.get(), bytes.data() + got, bytes.size() - got);
            if (n <= 0)
                return {};
            got += std::size_t(n);
        }
        return bytes;
    }

    std::vector<std::string> names_under(const std::string &folder, const std::string &extension) const
    {
        std::vector<std::string> out;
        for (const auto &[name, where] : files_)
            if (name.rfind(folder, 0) == 0 && name.size() > extension.size() &&
                name.compare(name.size() - extension.size(), extension.size(), extension) == 0)
                out.push_back(name);
        return out;
    }

private:
    std::vector<std::unique_ptr<zip_t, ArchiveCloser>> archives_;
    std::map<std::string, std::pair<std::size_t, zip_uint64_t>> files_;
};

// The words of a shader script: braces are words of their own, // and /* */
// comments are skipped, quotes group.
std::vector<std::string> words_of(const std::vector<char> &text)
{
    std::vector<std::string> words;
    std::size_t i = 0;
    const std::size_t n = text.size();
    while (i < n) {
        const char c = text[i];
        if (std::isspace(static_cast<unsigned char>(c))) {
            ++i;
        } else if (c == '/' && i + 1 < n && text[i + 1] == '/') {
            while (i < n && text[i] != '\n')
                ++i;
        } else if (c == '/' && i + 1 < n && text[i + 1] == '*') {
            i += 2;
            while (i + 1 < n && !(text[i] == '*' && text[i + 1] == '/'))
                ++i;
            i += 2;
        } else if (c == '{' || c == '}') {
            words.emplace_back(1, c);
            ++i;
        } else if (c == '"') {
            const std::size_t start = ++i;
            while (i < n && text[i] != '"' && text[i] != '\n')
                ++i;
            words.emplace_back(text.begin() + std::ptrdiff_t(start), text.begin() + std::ptrdiff_t(i));
            ++i;
        } else {
            const std::size_t start = i;
            while (i < n && !std::isspace(static_cast<unsigned char>(text[i])) && text[i] != '{' && text[i] != '}')
                ++i;
            words.emplace_back(text.begin() + std::ptrdiff_t(start), text.begin() + std::ptrdiff_t(i));
        }
    }
    return words;
}

// Shader name -> the picture of its first stage that draws one, for the
// shaders `wanted` names, from every script (the first definition of a
// name wins, as the game's lookup in its concatenated scripts does).
std::map<std::string, std::string> first_pictures(const SearchPath &files, const std::map<std::string, int> &wanted)
{
    std::map<std::string, std::string> out;
    std::map<std::string, bool> defined;
    for (const std::string &script : files.names_under("scripts/", ".shader")) {
        const std::vector<std::string> w = words_of(files.read(script));
        for (std::size_t i = 0; i < w.size();) {
            const std::string name = lower(w[i]);
            if (i + 1 >= w.size() || w[i + 1] != "{") {
                ++i;   // not a shader's opening: skip a stray word
                continue;
            }
            // The shader's body: depth 1 its keywords, depth 2 its stages.
            std::size_t k = i + 2;
            int depth = 1;
            std::string picture;
            for (; k < w.size() && depth > 0; ++k) {
                if (w[k] == "{") {
                    ++depth;
                } else if (w[k] == "}") {
                    --depth;
                } else if (depth == 2 && picture.empty() && k + 1 < w.size()) {
                    const std::string key = lower(w[k]);
                    std::size_t at = 0;
                    if (key == "map" || key == "clampmap")
                        at = k + 1;
                    else if (key == "animmap" && k + 2 < w.size())
                        at = k + 2;
                    if (at && w[at][0] != '$' && w[at] != "{" && w[at] != "}")
                        picture = w[at];
                }
            }
            if (wanted.count(name) && !defined[name]) {
                defined[name] = true;
                if (!picture.empty())
                    out[name] = picture;
            }
            i = k;
        }
    }
    return out;
}

// `name` without its extension, tried with .tga, then .jpg.
std::string find_picture(const SearchPath &files, const std::string &name)
{
    std::string stem = name;
    const std::size_t dot = stem.find_last_of('.'), slash = stem.find_last_of('/');
    if (dot != std::string::npos && (slash == std::string::npos || dot > slash))
        stem.erase(dot);
    for (const char *extension : {".tga", ".jpg"})
        if (files.has(stem + extension))
            return stem + extension;
    return "";
}

}  // namespace

void read_level_pictures(Scene &scene, const std::string &archive, std::vector<std::string> &warnings)
{
    const SearchPath files(std::filesystem::path(archive).parent_path().empty() ? std::filesystem::path(".")
                                                                              : std::filesystem::path(archive).parent_path());
    std::map<std::string, int> wanted;
    for (const Mesh &m : scene.meshes)
        if (m.shaded && !m.texcoords.empty())
            wanted[lower(m.name)] = 0;
    const std::map<std::string, std::string> shaders = first_pictures(files, wanted);

    std::map<std::string, std::int32_t> decoded;   // picture path -> scene.images index (-1: failed)
    std::vector<std::string> missing;
    for (Mesh &m : scene.meshes) {
        if (!m.shaded || m.texcoords.empty())
            continue;
        const std::string name = lower(m.name);
        const auto shader = shaders.find(name);
        const std::string path = find_picture(files, shader != shaders.end() ? shader->second : name);
        if (path.empty()) {
            missing.push_back(m.name);
            continue;
        }
        auto [it, fresh] = decoded.emplace(path, -1);
        if (fresh) {
            const std::vector<char> bytes = files.read(path);
            int w = 0, h = 0, channels = 0;
            stbi_uc *pixels = bytes.empty() ? nullptr
                                            : stbi_load_from_memory(reinterpret_cast<const stbi_uc *>(bytes.data()),
                                                                    int(bytes.size()), &w, &h, &channels, 4);
            if (pixels) {
                Image image;
                image.name = path;
                image.width = w;
                image.height = h;
                image.rgba.assign(pixels, pixels + std::size_t(w) * std::size_t(h) * 4);
                stbi_image_free(pixels);
                it->second = std::int32_t(scene.images.size());
                scene.images.push_back(std::move(image));
            } else {
                missing.push_back(m.name + " (" + path + ": " + (bytes.empty() ? "unreadable" : stbi_failure_reason()) + ")");
            }
        }
        m.image = it->second;
    }
    if (!missing.empty()) {
        std::string names;
        for (std::size_t i = 0; i < missing.size() && i < 5; ++i)
            names += (i ? ", " : "") + missing[i];
        warnings.push_back("scene '" + archive + "': " + std::to_string(missing.size()) +
                           " textures have no picture in the pk3 files beside it (" + names +
                           (missing.size() > 5 ? ", ..." : "") + "); drawn in their light alone");
    }
}

}  // namespace occu
