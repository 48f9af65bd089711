/* SPDX-License-Identifier: MIT */
/*
 * Helpers of the coarse-depth tests (coarse-depth-agrees.c,
 * coarse-depth-conservative.c): llvmpipe may reject an occlusion pass's
 * blocks against a coarse depth of the bin (LP_PERF=no_ou_coarse turns it
 * off, LP_PERF=ou_coarse_verify checks every rejection); these run scenes
 * in child processes, each with its own driver and environment, and bring
 * back what the child recorded as a transcript of words.
 */
#ifndef COARSE_UTIL_H
#define COARSE_UTIL_H

#define _DEFAULT_SOURCE 1   /* setenv, strsignal */
#include <GL/osmesa.h>
#include <stdlib.h>
#include <sys/select.h>
#include <sys/wait.h>
#include <unistd.h>

#include "ou_util.h"

/* What a child recorded, word by word; a header word (COARSE_HEADER | where)
 * before each record says which scene, pass and tile follow. */
struct transcript {
    GLuint *words;
    size_t n, capacity;
};

#define COARSE_HEADER 0xc0000000u

static inline void
transcript_add(struct transcript *t, GLuint w)
{
    if (t->n == t->capacity) {
        t->capacity = t->capacity ? 2 * t->capacity : 4096;
        t->words = realloc(t->words, t->capacity * sizeof(GLuint));
        if (!t->words) {
            fprintf(stderr, "out of memory for the transcript\n");
            _exit(3);
        }
    }
    t->words[t->n++] = w;
}

/* The header of (scene, pass, tile). */
static inline GLuint
coarse_where(unsigned scene, unsigned pass, unsigned tile)
{
    return COARSE_HEADER | (scene & 0xfff) << 16 | (pass & 0xff) << 8 | (tile & 0xff);
}

static inline void
coarse_print_where(GLuint header)
{
    printf("scene %u pass %u tile %u", (header >> 16) & 0xfff, (header >> 8) & 0xff, header & 0xff);
}

/* A 64-bit FNV-1a hash of n words: verbose lists are compared by their
 * count and hash, not carried whole through the pipe. */
static inline uint64_t
coarse_hash(const GLuint *w, size_t n)
{
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < n; ++i) {
        h ^= w[i];
        h *= 1099511628211ull;
    }
    return h;
}

/* Runs child(t) in a child process with GALLIUM_DRIVER `driver` and the
 * environment variables `env` ("NAME=value", NULL-terminated); the child's
 * stderr goes to `err` (size err_size, NUL-terminated). False, with the
 * reason printed, when the child crashed or exited with an error. */
static inline bool
coarse_run_child(const char *driver, const char *const *env, void (*child)(struct transcript *),
                 struct transcript *out, char *err, size_t err_size, const char *name)
{
    int fd[2], efd[2];
    if (pipe(fd) != 0 || pipe(efd) != 0) {
        perror("pipe");
        return false;
    }
    fflush(stdout);
    fflush(stderr);
    pid_t pid = fork();
    if (pid < 0) {
        perror("fork");
        return false;
    }
    if (pid == 0) {
        close(fd[0]);
        close(efd[0]);
        dup2(efd[1], 2);
        setenv("GALLIUM_DRIVER", driver, 1);
        unsetenv("LP_PERF");
        unsetenv("LP_NUM_THREADS");
        for (int i = 0; env && env[i]; ++i)
            putenv((char *)env[i]);
        struct transcript t = {0};
        child(&t);
        /* Destroying the context prints ou_coarse_verify's report. */
        OSMesaDestroyContext(OSMesaGetCurrentContext());
        const GLuint count = (GLuint)t.n;
        _exit(ou_write_all(fd[1], &count, sizeof(count)) &&
              ou_write_all(fd[1], t.words, t.n * sizeof(GLuint)) ? 0 : 1);
    }
    close(fd[1]);
    close(efd[1]);
    /* stderr first, in the background of the pipe's capacity: read both
     * until they close. */
    GLuint count = 0;
    size_t got = 0, egot = 0, want = sizeof(count);
    char *p = (char *)&count;
    bool counting = true, open_out = true, open_err = true;
    out->n = 0;
    while (open_out || open_err) {
        fd_set set;
        FD_ZERO(&set);
        if (open_out)
            FD_SET(fd[0], &set);
        if (open_err)
            FD_SET(efd[0], &set);
        if (select((fd[0] > efd[0] ? fd[0] : efd[0]) + 1, &set, NULL, NULL, NULL) < 0)
            break;
        if (open_err && FD_ISSET(efd[0], &set)) {
            char buf[4096];
            ssize_t k = read(efd[0], buf, sizeof(buf));
            if (k <= 0) {
                open_err = false;
            } else {
                size_t keep = (size_t)k < err_size - 1 - egot ? (size_t)k : err_size - 1 - egot;
                memcpy(err + egot, buf, keep);
                egot += keep;
            }
        }
        if (open_out && FD_ISSET(fd[0], &set)) {
            ssize_t k = read(fd[0], p + got, want - got);
            if (k <= 0) {
                open_out = false;
                continue;
            }
            got += (size_t)k;
            if (got == want && counting) {
                counting = false;
                out->capacity = count ? count : 1;
                out->words = realloc(out->words, out->capacity * sizeof(GLuint));
                p = (char *)out->words;
                got = 0;
                want = (size_t)count * sizeof(GLuint);
                if (!want)
                    open_out = false;
            } else if (got == want) {
                open_out = false;
            }
        }
    }
    err[egot] = 0;
    close(fd[0]);
    close(efd[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    if (WIFSIGNALED(status)) {
        printf("%s: child died of signal %d (%s); its stderr:\n%s\n", name, WTERMSIG(status),
               strsignal(WTERMSIG(status)), err);
        return false;
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        printf("%s: child exited with status %d; its stderr:\n%s\n", name,
               WIFEXITED(status) ? WEXITSTATUS(status) : -1, err);
        return false;
    }
    if (counting || got != want) {
        printf("%s: child reported an incomplete transcript\n", name);
        return false;
    }
    out->n = count;
    return true;
}

/* Whether two transcripts are equal word by word; the first difference is
 * printed with the scene, pass and tile it belongs to. */
static inline bool
coarse_same(const struct transcript *a, const struct transcript *b, const char *what)
{
    GLuint where = 0;
    size_t header = 0;
    size_t n = a->n < b->n ? a->n : b->n;
    for (size_t i = 0; i < n; ++i) {
        if ((a->words[i] & 0xf0000000u) == COARSE_HEADER) {
            where = a->words[i];
            header = i;
        }
        if (a->words[i] != b->words[i]) {
            printf("%s: word %zu (", what, i);
            coarse_print_where(where);
            printf(", word %zu after its header) is %u, expected %u; the words after the header:\n", i - header,
                   b->words[i], a->words[i]);
            for (size_t k = header + 1; k < n && k < header + 12 && (a->words[k] & 0xf0000000u) != COARSE_HEADER; ++k)
                printf("  %u: %u, expected %u\n", (unsigned)(k - header), b->words[k], a->words[k]);
            return false;
        }
    }
    if (a->n != b->n) {
        printf("%s: %zu words, expected %zu\n", what, b->n, a->n);
        return false;
    }
    return true;
}

/* The "rejected N of M pass blocks" line of LP_PERF=ou_coarse_verify in a
 * child's stderr: N, or -1 when there is no such line. */
/** A fragment program whose shader runs `body` before writing the colour,
 * with early fragment tests declared when `early`; a child exits 2 if it
 * does not build. */
static inline GLuint
coarse_build_program(const char *body, bool early)
{
    char source[1024];
    snprintf(source, sizeof(source),
             "#version 150 compatibility\n"
             "#extension GL_ARB_shader_image_load_store : require\n"
             "%s"
             "out vec4 colour;\n"
             "void main() {\n%s  colour = gl_Color;\n}\n",
             early ? "layout(early_fragment_tests) in;\n" : "", body);
    GLuint p = piglit_build_simple_program(NULL, source);
    if (!p) {
        fprintf(stderr, "a fragment shader did not build\n");
        _exit(2);
    }
    return p;
}

/* The checks a child could not pass, each printed to stderr by
 * coarse_check; the child reports the count in its transcript. */
static GLuint coarse_failures;

static inline void
coarse_check(bool ok, const char *what, unsigned got, unsigned expected)
{
    if (!ok) {
        fprintf(stderr, "%s: %u, expected %u\n", what, got, expected);
        ++coarse_failures;
    }
}

static inline long long
coarse_rejected(const char *err, long long *blocks)
{
    const char *line = strstr(err, "occlusion coarse depth rejected ");
    long long n = -1, m = -1;
    if (!line || sscanf(line, "occlusion coarse depth rejected %lld of %lld", &n, &m) != 2)
        return -1;
    if (blocks)
        *blocks = m;
    return n;
}

/* Depth formats of the scenes' framebuffer objects. */
struct coarse_format {
    GLenum internal;
    GLenum attachment;
    const char *name;
};

static const struct coarse_format coarse_formats[] = {
    {GL_DEPTH_COMPONENT16, GL_DEPTH_ATTACHMENT, "16"},
    {GL_DEPTH_COMPONENT24, GL_DEPTH_ATTACHMENT, "24"},
    {GL_DEPTH24_STENCIL8, GL_DEPTH_STENCIL_ATTACHMENT, "24_8"},
    {GL_DEPTH_COMPONENT32F, GL_DEPTH_ATTACHMENT, "32F"},
};

/* Makes and binds a framebuffer object of w x h with an RGBA8 colour
 * buffer and a depth buffer of `format`, of `samples` samples (0: single
 * sampled); fails the child (exit 2) when it is incomplete. */
static inline GLuint
coarse_make_fbo(const struct ou_fbo_functions *f, int w, int h, const struct coarse_format *format, int samples)
{
    GLuint fbo, rb[2];
    f->GenFramebuffers(1, &fbo);
    f->GenRenderbuffers(2, rb);
    const GLenum internal[2] = {GL_RGBA8, format->internal};
    for (int i = 0; i < 2; ++i) {
        f->BindRenderbuffer(GL_RENDERBUFFER, rb[i]);
        if (samples > 0)
            f->RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, internal[i], w, h);
        else
            f->RenderbufferStorage(GL_RENDERBUFFER, internal[i], w, h);
    }
    f->BindFramebuffer(GL_FRAMEBUFFER, fbo);
    f->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
    f->FramebufferRenderbuffer(GL_FRAMEBUFFER, format->attachment, GL_RENDERBUFFER, rb[1]);
    if (f->CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        fprintf(stderr, "a %dx%d framebuffer object with depth %s and %d samples is incomplete\n", w, h,
                format->name, samples);
        _exit(2);
    }
    glViewport(0, 0, w, h);
    return fbo;
}

#endif
