// SPDX-License-Identifier: MIT
// occu-egl-check: proves that an unmodified program linked to glvnd's libEGL
// and libOpenGL (as Debian's piglit binaries are) renders on occu's patched
// Mesa: it makes a surfaceless EGL context, prints GL_RENDERER and the
// libEGL_mesa glvnd loaded, and fails unless that library lies under the
// prefix given as argument and the renderer names $GALLIUM_DRIVER.
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <link.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

std::string loaded_library(const char *needle)
{
    std::string found;
    std::pair<const char *, std::string *> args(needle, &found);
    dl_iterate_phdr(
        [](dl_phdr_info *info, size_t, void *data) {
            auto *args = static_cast<std::pair<const char *, std::string *> *>(data);
            if (info->dlpi_name && std::strstr(info->dlpi_name, args->first))
                *args->second = info->dlpi_name;
            return 0;
        },
        &args);
    return found;
}

int fail(const char *what)
{
    std::fprintf(stderr, "occu-egl-check: %s (EGL error 0x%x)\n", what, eglGetError());
    return 1;
}

}  // namespace

int main(int argc, char **argv)
{
    if (argc != 2) {
        std::fprintf(stderr, "usage: occu-egl-check MESA_PREFIX\n");
        return 2;
    }
    const std::string prefix = argv[1];

    auto get_platform_display =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!get_platform_display)
        return fail("no eglGetPlatformDisplayEXT");
    EGLDisplay dpy = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, nullptr, nullptr))
        return fail("cannot initialize a surfaceless EGL display");
    if (!eglBindAPI(EGL_OPENGL_API))
        return fail("eglBindAPI(EGL_OPENGL_API) failed");
    // Surfaceless displays have no window configs, and EGL_WINDOW_BIT is the default.
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config;
    EGLint n = 0;
    if (!eglChooseConfig(dpy, config_attribs, &config, 1, &n) || n < 1)
        return fail("no EGL config for desktop OpenGL");
    EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, nullptr);
    if (ctx == EGL_NO_CONTEXT || !eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx))
        return fail("cannot make a surfaceless OpenGL context current");

    const char *renderer = reinterpret_cast<const char *>(glGetString(GL_RENDERER));
    const char *version = reinterpret_cast<const char *>(glGetString(GL_VERSION));
    const std::string vendor_lib = loaded_library("libEGL_mesa.so");
    std::printf("renderer: %s\nversion:  %s\nlibEGL_mesa: %s\n", renderer ? renderer : "(null)",
                version ? version : "(null)", vendor_lib.c_str());

    int status = 0;
    if (vendor_lib.rfind(prefix, 0) != 0) {
        std::fprintf(stderr, "occu-egl-check: glvnd loaded '%s', not the patched Mesa under %s\n",
                     vendor_lib.c_str(), prefix.c_str());
        status = 1;
    }
    const char *wanted = std::getenv("GALLIUM_DRIVER");
    if (wanted && (!renderer || !std::strstr(renderer, wanted))) {
        std::fprintf(stderr, "occu-egl-check: GALLIUM_DRIVER=%s but the renderer is '%s'\n", wanted,
                     renderer ? renderer : "(null)");
        status = 1;
    }
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, ctx);
    eglTerminate(dpy);
    return status;
}
