// bedlam — the OpenGL 3.3 core functions the renderer uses, loaded at run time.
//
// Every context backend (SDL2, EGL, OSMesa) hands out its own function addresses, so nothing links
// against libGL: bdl_gl_load fills one table of pointers from the backend's lookup function, and
// the `gl*` names below are macros onto that table. One X-macro list is the only place a function
// is named.
#ifndef BDL_GL_H
#define BDL_GL_H

#include <GL/glcorearb.h>

#define BDL_GL_FUNCTIONS(X)                                                                        \
    X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                                                       \
    X(PFNGLATTACHSHADERPROC, AttachShader)                                                         \
    X(PFNGLBINDBUFFERPROC, BindBuffer)                                                             \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                                                   \
    X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                                                 \
    X(PFNGLBINDTEXTUREPROC, BindTexture)                                                           \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                                                   \
    X(PFNGLBLENDFUNCPROC, BlendFunc)                                                               \
    X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer)                                                   \
    X(PFNGLBUFFERDATAPROC, BufferData)                                                             \
    X(PFNGLBUFFERSUBDATAPROC, BufferSubData)                                                       \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)                                     \
    X(PFNGLCLEARPROC, Clear)                                                                       \
    X(PFNGLCLEARCOLORPROC, ClearColor)                                                             \
    X(PFNGLCOMPILESHADERPROC, CompileShader)                                                       \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                                       \
    X(PFNGLCREATESHADERPROC, CreateShader)                                                         \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                                       \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                                             \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                                       \
    X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)                                           \
    X(PFNGLDELETESHADERPROC, DeleteShader)                                                         \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                                     \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                                             \
    X(PFNGLDEPTHFUNCPROC, DepthFunc)                                                               \
    X(PFNGLDEPTHMASKPROC, DepthMask)                                                               \
    X(PFNGLDISABLEPROC, Disable)                                                                   \
    X(PFNGLDRAWARRAYSPROC, DrawArrays)                                                             \
    X(PFNGLDRAWARRAYSINSTANCEDPROC, DrawArraysInstanced)                                           \
    X(PFNGLENABLEPROC, Enable)                                                                     \
    X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)                                   \
    X(PFNGLFINISHPROC, Finish)                                                                     \
    X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)                                   \
    X(PFNGLGENBUFFERSPROC, GenBuffers)                                                             \
    X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                                                   \
    X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                                                 \
    X(PFNGLGENTEXTURESPROC, GenTextures)                                                           \
    X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                                                   \
    X(PFNGLGETERRORPROC, GetError)                                                                 \
    X(PFNGLGETFLOATVPROC, GetFloatv)                                                               \
    X(PFNGLGETINTEGERVPROC, GetIntegerv)                                                           \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                                               \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                                         \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                                                 \
    X(PFNGLGETSHADERIVPROC, GetShaderiv)                                                           \
    X(PFNGLGETSTRINGPROC, GetString)                                                               \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                                             \
    X(PFNGLLINKPROGRAMPROC, LinkProgram)                                                           \
    X(PFNGLPIXELSTOREIPROC, PixelStorei)                                                           \
    X(PFNGLREADBUFFERPROC, ReadBuffer)                                                             \
    X(PFNGLREADPIXELSPROC, ReadPixels)                                                             \
    X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)                                           \
    X(PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC, RenderbufferStorageMultisample)                     \
    X(PFNGLSHADERSOURCEPROC, ShaderSource)                                                         \
    X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                                             \
    X(PFNGLTEXPARAMETERIPROC, TexParameteri)                                                       \
    X(PFNGLUNIFORM1FPROC, Uniform1f)                                                               \
    X(PFNGLUNIFORM1IPROC, Uniform1i)                                                               \
    X(PFNGLUNIFORM2FPROC, Uniform2f)                                                               \
    X(PFNGLUNIFORM3FPROC, Uniform3f)                                                               \
    X(PFNGLUNIFORM4FPROC, Uniform4f)                                                               \
    X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                                                 \
    X(PFNGLUSEPROGRAMPROC, UseProgram)                                                             \
    X(PFNGLVERTEXATTRIBDIVISORPROC, VertexAttribDivisor)                                           \
    X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                                           \
    X(PFNGLVIEWPORTPROC, Viewport)

#define BDL_GL_DECLARE(type, name) extern type bdl_gl##name;
BDL_GL_FUNCTIONS(BDL_GL_DECLARE)
#undef BDL_GL_DECLARE

typedef void (*bdl_gl_proc)(void);
typedef bdl_gl_proc (*bdl_gl_lookup)(const char *name);

/// Fills the function table through `lookup`. Returns the name of the first function that could
/// not be found, or NULL when all were.
const char *bdl_gl_load(bdl_gl_lookup lookup);

#define glActiveTexture                  bdl_glActiveTexture
#define glAttachShader                   bdl_glAttachShader
#define glBindBuffer                     bdl_glBindBuffer
#define glBindFramebuffer                bdl_glBindFramebuffer
#define glBindRenderbuffer               bdl_glBindRenderbuffer
#define glBindTexture                    bdl_glBindTexture
#define glBindVertexArray                bdl_glBindVertexArray
#define glBlendFunc                      bdl_glBlendFunc
#define glBlitFramebuffer                bdl_glBlitFramebuffer
#define glBufferData                     bdl_glBufferData
#define glBufferSubData                  bdl_glBufferSubData
#define glCheckFramebufferStatus         bdl_glCheckFramebufferStatus
#define glClear                          bdl_glClear
#define glClearColor                     bdl_glClearColor
#define glCompileShader                  bdl_glCompileShader
#define glCreateProgram                  bdl_glCreateProgram
#define glCreateShader                   bdl_glCreateShader
#define glDeleteBuffers                  bdl_glDeleteBuffers
#define glDeleteFramebuffers             bdl_glDeleteFramebuffers
#define glDeleteProgram                  bdl_glDeleteProgram
#define glDeleteRenderbuffers            bdl_glDeleteRenderbuffers
#define glDeleteShader                   bdl_glDeleteShader
#define glDeleteTextures                 bdl_glDeleteTextures
#define glDeleteVertexArrays             bdl_glDeleteVertexArrays
#define glDepthFunc                      bdl_glDepthFunc
#define glDepthMask                      bdl_glDepthMask
#define glDisable                        bdl_glDisable
#define glDrawArrays                     bdl_glDrawArrays
#define glDrawArraysInstanced            bdl_glDrawArraysInstanced
#define glEnable                         bdl_glEnable
#define glEnableVertexAttribArray        bdl_glEnableVertexAttribArray
#define glFinish                         bdl_glFinish
#define glFramebufferRenderbuffer        bdl_glFramebufferRenderbuffer
#define glGenBuffers                     bdl_glGenBuffers
#define glGenFramebuffers                bdl_glGenFramebuffers
#define glGenRenderbuffers               bdl_glGenRenderbuffers
#define glGenTextures                    bdl_glGenTextures
#define glGenVertexArrays                bdl_glGenVertexArrays
#define glGetError                       bdl_glGetError
#define glGetFloatv                      bdl_glGetFloatv
#define glGetIntegerv                    bdl_glGetIntegerv
#define glGetProgramInfoLog              bdl_glGetProgramInfoLog
#define glGetProgramiv                   bdl_glGetProgramiv
#define glGetShaderInfoLog               bdl_glGetShaderInfoLog
#define glGetShaderiv                    bdl_glGetShaderiv
#define glGetString                      bdl_glGetString
#define glGetUniformLocation             bdl_glGetUniformLocation
#define glLinkProgram                    bdl_glLinkProgram
#define glPixelStorei                    bdl_glPixelStorei
#define glReadBuffer                     bdl_glReadBuffer
#define glReadPixels                     bdl_glReadPixels
#define glRenderbufferStorage            bdl_glRenderbufferStorage
#define glRenderbufferStorageMultisample bdl_glRenderbufferStorageMultisample
#define glShaderSource                   bdl_glShaderSource
#define glTexImage2D                     bdl_glTexImage2D
#define glTexParameteri                  bdl_glTexParameteri
#define glUniform1f                      bdl_glUniform1f
#define glUniform1i                      bdl_glUniform1i
#define glUniform2f                      bdl_glUniform2f
#define glUniform3f                      bdl_glUniform3f
#define glUniform4f                      bdl_glUniform4f
#define glUniformMatrix4fv               bdl_glUniformMatrix4fv
#define glUseProgram                     bdl_glUseProgram
#define glVertexAttribDivisor            bdl_glVertexAttribDivisor
#define glVertexAttribPointer            bdl_glVertexAttribPointer
#define glViewport                       bdl_glViewport

#endif
