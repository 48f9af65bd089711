// SPDX-License-Identifier: MIT
// occu-info: which Mesa occu renders with, per gallium driver, and whether
// that Mesa advertises GL_MESAX_occlusion_unit.
//
// Mesa chooses the gallium driver once per process, so each driver is probed
// in a child process of its own.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <exception>

#include "gl/extensions.h"
#include "gl/offscreen_context.h"

namespace {

constexpr const char *kExtension = "GL_MESAX_occlusion_unit";

int probe(occu::gl::Driver driver)
{
    using namespace occu::gl;
    try {
        select_driver(driver);
        OffscreenContext ctx(64, 64);
        const std::string renderer = ctx.renderer();
        const bool is_driver = renderer.find(driver_name(driver)) != std::string::npos;
        std::printf("%-9s renderer: %s\n", driver_name(driver), renderer.c_str());
        std::printf("%-9s version:  %s\n", "", ctx.version().c_str());
        std::printf("%-9s %s: %s\n", "", kExtension, has_extension(kExtension) ? "advertised" : "not advertised");
        if (!is_driver) {
            std::fprintf(stderr, "occu-info: asked for %s but Mesa renders with '%s'\n", driver_name(driver),
                         renderer.c_str());
            return 1;
        }
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "occu-info: %s: %s\n", driver_name(driver), e.what());
        return 1;
    }
}

}  // namespace

int main(int argc, char **argv)
{
    if (argc > 1) {
        const bool help = std::strcmp(argv[1], "-h") == 0 || std::strcmp(argv[1], "--help") == 0;
        std::fprintf(help ? stdout : stderr,
                     "usage: occu-info\n"
                     "Prints, for softpipe and llvmpipe, the OSMesa renderer, GL version and\n"
                     "whether %s is advertised.\n", kExtension);
        if (!help)
            std::fprintf(stderr, "occu-info: unexpected argument '%s'\n", argv[1]);
        return help ? 0 : 2;
    }
    int failures = 0;
    for (occu::gl::Driver d : {occu::gl::Driver::softpipe, occu::gl::Driver::llvmpipe}) {
        std::fflush(stdout);
        const pid_t pid = fork();
        if (pid == 0) {
            const int rc = probe(d);  // stdout is a pipe under CI: flush before _exit
            std::fflush(stdout);
            _exit(rc);
        }
        int status = 0;
        if (pid < 0 || waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
            ++failures;
    }
    return failures == 0 ? 0 : 1;
}
