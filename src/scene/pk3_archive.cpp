// SPDX-License-Identifier: MIT
#include "scene/pk3_archive.h"

#include <zip.h>

#include <algorithm>
#include <cctype>
#include <memory>
#include <stdexcept>

namespace occu {

namespace {

std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

bool ends_with(const std::string &s, const std::string &tail)
{
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

struct ArchiveCloser {
    void operator()(zip_t *z) const { zip_discard(z); }
};
struct FileCloser {
    void operator()(zip_file_t *f) const { zip_fclose(f); }
};

}  // namespace

bool split_pk3_path(const std::string &path, std::string &archive, std::string &member)
{
    const std::size_t at = lower(path).find(".pk3:");
    if (at == std::string::npos)
        return false;
    archive = path.substr(0, at + 4);
    member = path.substr(at + 5);
    return true;
}

std::vector<char> read_pk3_member(const std::string &archive, const std::string &member, std::uint64_t max_bytes)
{
    const std::string what = "cannot read scene '" + archive + ":" + member + "': ";
    int error = 0;
    std::unique_ptr<zip_t, ArchiveCloser> zip(zip_open(archive.c_str(), ZIP_RDONLY, &error));
    if (!zip) {
        zip_error_t e;
        zip_error_init_with_code(&e, error);
        const std::string reason = zip_error_strerror(&e);
        zip_error_fini(&e);
        throw std::runtime_error(what + "cannot open the archive '" + archive + "': " + reason);
    }
    const zip_int64_t index = zip_name_locate(zip.get(), member.c_str(), ZIP_FL_NOCASE);
    if (index < 0) {
        std::string levels;
        int listed = 0;
        const zip_int64_t entries = zip_get_num_entries(zip.get(), 0);
        for (zip_int64_t i = 0; i < entries && listed < 10; ++i) {
            const char *name = zip_get_name(zip.get(), zip_uint64_t(i), 0);
            if (!name)
                continue;
            const std::string n = lower(name);
            if (n.rfind("maps/", 0) == 0 && ends_with(n, ".bsp")) {
                levels += (listed ? ", " : "") + std::string(name);
                ++listed;
            }
        }
        throw std::runtime_error(what + "the archive '" + archive + "' holds no member '" + member + "'" +
                                 (listed ? " (its levels include " + levels + ")" : " (nor any maps/*.bsp)"));
    }
    zip_stat_t stat;
    zip_stat_init(&stat);
    if (zip_stat_index(zip.get(), zip_uint64_t(index), 0, &stat) != 0 || !(stat.valid & ZIP_STAT_SIZE))
        throw std::runtime_error(what + "the archive gives no size for the member: " + zip_strerror(zip.get()));
    if (stat.size > max_bytes)
        throw std::runtime_error(what + "the member is " + std::to_string(stat.size) + " bytes, more than the " +
                                 std::to_string(max_bytes) + " a scene may be");
    std::unique_ptr<zip_file_t, FileCloser> file(zip_fopen_index(zip.get(), zip_uint64_t(index), 0));
    if (!file)
        throw std::runtime_error(what + "cannot open the member: " + zip_strerror(zip.get()));
    std::vector<char> bytes(std::size_t(stat.size));
    std::size_t got = 0;
    while (got < bytes.size()) {
        const zip_int64_t n = zip_fread(file.get(), bytes.data() + got, bytes.size() - got);
        if (n < 0)
            throw std::runtime_error(what + "the member's data is damaged: " + zip_file_strerror(file.get()));
        if (n == 0)
            break;
        got += std::size_t(n);
    }
    // One byte more must find the end; reading to it checks the CRC.
    char extra;
    if (got != bytes.size() || zip_fread(file.get(), &extra, 1) != 0)
        throw std::runtime_error(what + "the member's data is not the " + std::to_string(stat.size) +
                                 " bytes its directory entry says (or its CRC does not match)");
    return bytes;
}

}  // namespace occu
