// SPDX-License-Identifier: MIT
// Fuzzes the reader every database shares (culling/database_file.h), as the
// database provider reads a file it finds (any kind, its provenance, then
// its records to the end) and with every kind of field a payload reads: any
// bytes are read to their end record, or refused naming the file; a number
// it gives is finite.
#include <cmath>

#include "culling/database_file.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    const occu::fuzz::InputFile file(data, size, ".db");
    try {
        occu::DatabaseReader in(file.path(), "", 0, "database");
        if (!std::isfinite(in.setting("a", -1e300, 1e300)))
            std::abort();
        if (!std::isfinite(in.scene_number("b", 0, 1e9)))
            std::abort();
    } catch (const std::runtime_error &e) {
        occu::fuzz::require_named(e, file.path());
    }
    try {
        occu::DatabaseReader in(file.path(), "", 0, "database");
        for (std::size_t records = 0; in.next(); ++records) {
            // Each field as the record's place in the file says: a word, a
            // count, a number, a float, or the rest of the line.
            for (std::size_t field = records; in.more(); ++field) {
                switch (field % 5) {
                case 0: (void)in.word("w"); break;
                case 1: (void)in.count("n", 1000); break;
                case 2: if (!std::isfinite(in.number("x"))) std::abort(); break;
                case 3: if (!std::isfinite(in.float_number("y"))) std::abort(); break;
                default: (void)in.rest(); break;
                }
            }
            in.done();
        }
    } catch (const std::runtime_error &e) {
        occu::fuzz::require_named(e, file.path());
    }
    return 0;
}
