// SPDX-License-Identifier: MIT
// Members of Quake III's pk3 archives (zip files), read through libzip:
// a scene named "ARCHIVE.pk3:MEMBER" is MEMBER inside ARCHIVE.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace occu {

// Splits "ARCHIVE.pk3:MEMBER" (the extension in any case) at its first
// ".pk3:"; false, leaving the outputs alone, for a name without one.
bool split_pk3_path(const std::string &path, std::string &archive, std::string &member);

// The bytes of `member` (matched as Quake III does, ignoring case) in the
// zip archive `archive`. Throws std::runtime_error beginning "cannot read
// scene '<archive>:<member>': " when the archive cannot be opened or is not
// a zip file, when it has no such member (naming up to ten of its members
// under maps/ ending .bsp), when the member is larger than `max_bytes`, or
// when its data is damaged (a CRC or inflate error).
std::vector<char> read_pk3_member(const std::string &archive, const std::string &member,
                                  std::uint64_t max_bytes = std::uint64_t(1) << 28);

}  // namespace occu
