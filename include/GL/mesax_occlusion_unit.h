/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: tokens and entry-point types, as
 * spec/MESAX_occlusion_unit.txt defines them. Include after <GL/gl.h>;
 * fetch the entry points with the platform's GetProcAddress. The token
 * values lie in no vendor's block of the Khronos registry (spec, issue 16).
 */
#ifndef GL_MESAX_occlusion_unit
#define GL_MESAX_occlusion_unit 1

#define GL_BRIEF_OCCLUSION_MESAX           0xFFE0
#define GL_VERBOSE_OCCLUSION_MESAX         0xFFE1
#define GL_MAX_OCCLUSION_TILES_MESAX       0xFFE2
#define GL_OCCLUSION_TILE_COUNT_MESAX      0xFFE3
#define GL_OCCLUSION_TILE_MESAX            0xFFE4
#define GL_OCCLUSION_BUFFER_COUNT_MESAX    0xFFE5
#define GL_OCCLUSION_BUFFER_SIZE_MESAX     0xFFE6
#define GL_OCCLUSION_BUFFER_POINTER_MESAX  0xFFE7

typedef void (APIENTRYP PFNGLSCISSORSMESAXPROC)(GLsizei count, const GLint *tiles);
typedef void (APIENTRYP PFNGLOCCLUSIONBUFFERSMESAXPROC)(GLsizei count, const GLsizei *sizes,
                                                        GLuint *const *buffers);

#endif

/*
 * GL_MESAX_occlusion_unit_async: named occlusion passes whose records are
 * read when they are ready, and conditional rendering on one tile of a
 * pass, as spec/MESAX_occlusion_unit_async.txt defines them.
 */
#ifndef GL_MESAX_occlusion_unit_async
#define GL_MESAX_occlusion_unit_async 1

#define GL_OCCLUSION_PASS_RESULT_MESAX            0xFFE8
#define GL_OCCLUSION_PASS_RESULT_AVAILABLE_MESAX  0xFFE9
#define GL_OCCLUSION_PASS_RESULT_NO_WAIT_MESAX    0xFFEA
#define GL_CURRENT_OCCLUSION_PASS_MESAX           0xFFEB

typedef void (APIENTRYP PFNGLGENOCCLUSIONPASSESMESAXPROC)(GLsizei n, GLuint *passes);
typedef void (APIENTRYP PFNGLDELETEOCCLUSIONPASSESMESAXPROC)(GLsizei n, const GLuint *passes);
typedef GLboolean (APIENTRYP PFNGLISOCCLUSIONPASSMESAXPROC)(GLuint pass);
typedef void (APIENTRYP PFNGLBEGINOCCLUSIONPASSMESAXPROC)(GLenum mode, GLuint pass);
typedef void (APIENTRYP PFNGLENDOCCLUSIONPASSMESAXPROC)(void);
typedef void (APIENTRYP PFNGLGETOCCLUSIONPASSIVMESAXPROC)(GLuint pass, GLenum pname, GLint *params);
typedef void (APIENTRYP PFNGLBEGINCONDITIONALRENDEROCCLUSIONTILEMESAXPROC)(GLuint pass, GLuint tile,
                                                                          GLuint minNohc, GLfloat minRatio,
                                                                          GLenum mode);
typedef void (APIENTRYP PFNGLENDCONDITIONALRENDEROCCLUSIONTILEMESAXPROC)(void);

#endif

/*
 * GL_MESAX_occlusion_unit_conservative: a pass whose records say only
 * whether some fragment of a tile may have passed, as
 * spec/MESAX_occlusion_unit_conservative.txt defines them.
 */
#ifndef GL_MESAX_occlusion_unit_conservative
#define GL_MESAX_occlusion_unit_conservative 1

#define GL_CONSERVATIVE_OCCLUSION_MESAX           0xFFEC

#endif
