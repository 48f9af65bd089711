/* SPDX-License-Identifier: MIT */
#include "piglit-util-gl.h"

#include <GL/osmesa.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PIGLIT_DEFINE_DISPATCH(type, name) type piglit_dispatch_##name;
PIGLIT_OSMESA_UNEXPORTED(PIGLIT_DEFINE_DISPATCH)
#undef PIGLIT_DEFINE_DISPATCH

int piglit_width, piglit_height;
unsigned int piglit_winsys_fbo;
static OSMesaContext context;
static unsigned char *color_buffer;
/* Subtests reported so far, by result: a program whose subtests all
 * skipped has tested nothing, and says so (piglit_report_result). */
static unsigned subtests_reported[PIGLIT_SKIP + 1];

static const char *result_name(enum piglit_result r)
{
    switch (r) {
    case PIGLIT_PASS: return "pass";
    case PIGLIT_FAIL: return "fail";
    default: return "skip";
    }
}

void piglit_report_result(enum piglit_result result)
{
    /* piglit's runner takes the worst subtest as the test's result: a
     * failed subtest fails it, and subtests that all skipped make it a
     * skip. meson reads the exit status alone, which must say the same. */
    if (result == PIGLIT_PASS && subtests_reported[PIGLIT_FAIL] > 0) {
        printf("%u subtests failed: the test reports a failure\n", subtests_reported[PIGLIT_FAIL]);
        result = PIGLIT_FAIL;
    } else if (result == PIGLIT_PASS && subtests_reported[PIGLIT_SKIP] > 0 && subtests_reported[PIGLIT_PASS] == 0) {
        printf("every subtest (%u) skipped: the test reports a skip, not a pass\n", subtests_reported[PIGLIT_SKIP]);
        result = PIGLIT_SKIP;
    }
    printf("PIGLIT: {\"result\": \"%s\" }\n", result_name(result));
    fflush(stdout);
    if (context)
        OSMesaDestroyContext(context);
    free(color_buffer);
    /* piglit's runner wants 0 for a skip (the result line says skip); meson
     * reads a skip from exit code 77, and its tests set OCCU_SKIP_EXIT_CODE. */
    int skip_code = 0;
    const char *env = getenv("OCCU_SKIP_EXIT_CODE");
    if (env)
        skip_code = atoi(env);
    exit(result == PIGLIT_PASS ? 0 : result == PIGLIT_SKIP ? skip_code : 1);
}

void piglit_report_subtest_result(enum piglit_result result, const char *format, ...)
{
    char name[512];
    va_list ap;
    va_start(ap, format);
    vsnprintf(name, sizeof(name), format, ap);
    va_end(ap);
    printf("PIGLIT: {\"subtest\": {\"%s\" : \"%s\"}}\n", name, result_name(result));
    subtests_reported[result == PIGLIT_PASS ? PIGLIT_PASS : result == PIGLIT_FAIL ? PIGLIT_FAIL : PIGLIT_SKIP]++;
    fflush(stdout);
}

void piglit_merge_result(enum piglit_result *all, enum piglit_result subtest)
{
    if (*all == PIGLIT_FAIL || subtest == PIGLIT_FAIL)
        *all = PIGLIT_FAIL;
    else if (*all == PIGLIT_PASS || subtest == PIGLIT_PASS)
        *all = PIGLIT_PASS;
    else
        *all = PIGLIT_SKIP;
}

/* Makes the OSMesa context and its buffer of width x height current. */
static void make_context(const struct piglit_gl_test_config *config)
{
    const int width = config->window_width, height = config->window_height;
    const bool core = !config->supports_gl_compat_version && config->supports_gl_core_version;
    int attribs[32], n = 0;
    attribs[n++] = OSMESA_FORMAT;
    attribs[n++] = OSMESA_RGBA;
    attribs[n++] = OSMESA_DEPTH_BITS;
    attribs[n++] = config->window_visual & PIGLIT_GL_VISUAL_DEPTH ? 24 : 0;
    attribs[n++] = OSMESA_STENCIL_BITS;
    attribs[n++] = config->window_visual & PIGLIT_GL_VISUAL_STENCIL ? 8 : 0;
    attribs[n++] = OSMESA_ACCUM_BITS;
    attribs[n++] = config->window_visual & PIGLIT_GL_VISUAL_ACCUM ? 16 : 0;
    attribs[n++] = OSMESA_PROFILE;
    attribs[n++] = core ? OSMESA_CORE_PROFILE : OSMESA_COMPAT_PROFILE;
    if (core) {
        attribs[n++] = OSMESA_CONTEXT_MAJOR_VERSION;
        attribs[n++] = config->supports_gl_core_version / 10;
        attribs[n++] = OSMESA_CONTEXT_MINOR_VERSION;
        attribs[n++] = config->supports_gl_core_version % 10;
    }
    attribs[n] = 0;
    context = OSMesaCreateContextAttribs(attribs, NULL);
    color_buffer = calloc((size_t)width * (size_t)height, 4);
    if (!context || !color_buffer ||
        !OSMesaMakeCurrent(context, color_buffer, GL_UNSIGNED_BYTE, width, height)) {
        fprintf(stderr, "could not make an OSMesa %s context of %dx%d\n", core ? "core" : "compatibility", width,
                height);
        piglit_report_result(PIGLIT_FAIL);
    }
    OSMesaPixelStore(OSMESA_Y_UP, 1);
#define PIGLIT_RESOLVE_DISPATCH(type, name) \
    piglit_dispatch_##name = (type)(void (*)(void))OSMesaGetProcAddress(#name);
    PIGLIT_OSMESA_UNEXPORTED(PIGLIT_RESOLVE_DISPATCH)
#undef PIGLIT_RESOLVE_DISPATCH
    piglit_width = width;
    piglit_height = height;
    glViewport(0, 0, width, height);
}

void piglit_gl_test_config_init(struct piglit_gl_test_config *config)
{
    /* piglit's defaults. */
    memset(config, 0, sizeof(*config));
    config->window_width = 160;
    config->window_height = 160;
    config->window_visual = PIGLIT_GL_VISUAL_RGB | PIGLIT_GL_VISUAL_DOUBLE;
}

void piglit_gl_process_args(int *argc, char *argv[], struct piglit_gl_test_config *config)
{
    (void)config;
    /* Every occu test is automatic and off-screen: -auto and -fbo change
     * nothing here, and piglit_init does not see them, as under piglit. */
    int kept = 1;
    for (int i = 1; i < *argc; ++i) {
        if (strcmp(argv[i], "-auto") && strcmp(argv[i], "-fbo"))
            argv[kept++] = argv[i];
    }
    argv[kept] = NULL;
    *argc = kept;
}

void piglit_gl_test_run(int argc, char *argv[], const struct piglit_gl_test_config *config)
{
    make_context(config);
    if (config->init)
        config->init(argc, argv);
    piglit_report_result(config->display ? config->display() : PIGLIT_PASS);
}

void piglit_osmesa_init(int argc, char **argv, int width, int height)
{
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "-auto") && strcmp(argv[i], "-fbo")) {
            fprintf(stderr, "%s: unknown argument '%s' (accepted: -auto -fbo)\n", argv[0], argv[i]);
            piglit_report_result(PIGLIT_FAIL);
        }
    }
    struct piglit_gl_test_config config;
    piglit_gl_test_config_init(&config);
    config.supports_gl_compat_version = 10;
    config.window_width = width;
    config.window_height = height;
    config.window_visual = PIGLIT_GL_VISUAL_RGBA | PIGLIT_GL_VISUAL_DEPTH | PIGLIT_GL_VISUAL_STENCIL;
    make_context(&config);
}

bool piglit_is_extension_supported(const char *name)
{
    const char *list = (const char *)glGetString(GL_EXTENSIONS);
    size_t n = strlen(name);
    for (const char *p = list; p && (p = strstr(p, name)); p += n) {
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0'))
            return true;
    }
    return false;
}

void piglit_require_extension(const char *name)
{
    if (!piglit_is_extension_supported(name)) {
        printf("Test requires %s, which %s does not advertise\n", name, (const char *)glGetString(GL_RENDERER));
        piglit_report_result(PIGLIT_SKIP);
    }
}

bool piglit_check_gl_error(GLenum expected)
{
    GLenum got = glGetError();
    if (got == expected)
        return true;
    printf("Unexpected GL error: 0x%04x, expected 0x%04x\n", got, expected);
    return false;
}

GLuint piglit_build_simple_program(const char *vertex_source, const char *fragment_source)
{
    PFNGLCREATESHADERPROC CreateShader = glCreateShader;
    PFNGLSHADERSOURCEPROC ShaderSource = glShaderSource;
    PFNGLCOMPILESHADERPROC CompileShader = glCompileShader;
    PFNGLCREATEPROGRAMPROC CreateProgram = glCreateProgram;
    PFNGLATTACHSHADERPROC AttachShader = glAttachShader;
    PFNGLLINKPROGRAMPROC LinkProgram = glLinkProgram;
    PFNGLGETPROGRAMIVPROC GetProgramiv = glGetProgramiv;
    PFNGLGETPROGRAMINFOLOGPROC GetProgramInfoLog =
        glGetProgramInfoLog;
    PFNGLGETSHADERIVPROC GetShaderiv = glGetShaderiv;
    PFNGLGETSHADERINFOLOGPROC GetShaderInfoLog =
        glGetShaderInfoLog;
    if (!CreateShader || !ShaderSource || !CompileShader || !CreateProgram || !AttachShader || !LinkProgram ||
        !GetProgramiv || !GetProgramInfoLog || !GetShaderiv || !GetShaderInfoLog) {
        printf("GL 2.0 shader entry points are missing\n");
        piglit_report_result(PIGLIT_FAIL);
    }
    const struct {
        GLenum type;
        const char *name;
        const char *source;
    } stages[2] = {{GL_VERTEX_SHADER, "vertex", vertex_source}, {GL_FRAGMENT_SHADER, "fragment", fragment_source}};
    GLuint program = CreateProgram();
    for (int i = 0; i < 2; ++i) {
        if (!stages[i].source)
            continue;
        GLuint shader = CreateShader(stages[i].type);
        ShaderSource(shader, 1, &stages[i].source, NULL);
        CompileShader(shader);
        GLint compiled = 0;
        GetShaderiv(shader, GL_COMPILE_STATUS, &compiled);
        if (!compiled) {
            char log[1024];
            GetShaderInfoLog(shader, sizeof(log), NULL, log);
            printf("%s shader failed to compile: %s\n", stages[i].name, log);
            piglit_report_result(PIGLIT_FAIL);
        }
        AttachShader(program, shader);
    }
    LinkProgram(program);
    GLint linked = 0;
    GetProgramiv(program, GL_LINK_STATUS, &linked);
    if (!linked) {
        char log[1024];
        GetProgramInfoLog(program, sizeof(log), NULL, log);
        printf("program failed to link: %s\n", log);
        piglit_report_result(PIGLIT_FAIL);
    }
    return program;
}
