// bedlam — GL helpers the parts of the renderer share: programs from the embedded shaders and
// byte textures.
#include <stdio.h>

#include "render/renderer_internal.h"

const char *bdl_shader_source(const char *name); // generated from shaders/

/// 0 when a shader compiled (`program` 0) or a program linked; else its log after `what` into
/// `why`, and 1.
static int failed(GLuint object, int program, const char *what, char *why, size_t why_len)
{
    GLint ok = 0;
    if (program)
        glGetProgramiv(object, GL_LINK_STATUS, &ok);
    else
        glGetShaderiv(object, GL_COMPILE_STATUS, &ok);
    if (ok)
        return 0;
    char log[1024] = "";
    if (program)
        glGetProgramInfoLog(object, sizeof log, NULL, log);
    else
        glGetShaderInfoLog(object, sizeof log, NULL, log);
    snprintf(why, why_len, "%s: %s", what, log);
    return 1;
}

static GLuint compile(GLenum kind, const char *name, char *why, size_t why_len)
{
    const char *source = bdl_shader_source(name);
    if (!source) {
        snprintf(why, why_len, "shader %s is not embedded", name);
        return 0;
    }
    GLuint s = glCreateShader(kind);
    glShaderSource(s, 1, &source, NULL);
    glCompileShader(s);
    char what[256];
    snprintf(what, sizeof what, "shader %s does not compile", name);
    if (failed(s, 0, what, why, why_len)) {
        glDeleteShader(s);
        return 0;
    }
    return s;
}

GLuint bdl_gl_program(const char *vert, const char *frag, char *why, size_t why_len)
{
    GLuint v = compile(GL_VERTEX_SHADER, vert, why, why_len);
    GLuint f = v ? compile(GL_FRAGMENT_SHADER, frag, why, why_len) : 0;
    if (!f) {
        if (v)
            glDeleteShader(v);
        return 0;
    }
    GLuint p = glCreateProgram();
    glAttachShader(p, v);
    glAttachShader(p, f);
    glLinkProgram(p);
    glDeleteShader(v);
    glDeleteShader(f);
    char what[256];
    snprintf(what, sizeof what, "shaders %s + %s do not link", vert, frag);
    if (failed(p, 1, what, why, why_len)) {
        glDeleteProgram(p);
        return 0;
    }
    return p;
}

GLuint bdl_gl_texture_2d(GLenum internal, int w, int h, GLenum format, const void *data,
                         GLint filter)
{
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)internal, w, h, 0, format, GL_UNSIGNED_BYTE, data);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return t;
}

int bdl_gl_mesh_create(bdl_gl_mesh *m, const char *vert, const char *frag, char *why,
                       size_t why_len)
{
    m->program = bdl_gl_program(vert, frag, why, why_len);
    if (!m->program)
        return 0;
    glGenVertexArrays(1, &m->vao);
    glBindVertexArray(m->vao);
    glGenBuffers(1, &m->vbo);
    glBindBuffer(GL_ARRAY_BUFFER, m->vbo);
    return 1;
}

void bdl_gl_mesh_destroy(bdl_gl_mesh *m)
{
    if (m->program)
        glDeleteProgram(m->program);
    if (m->vao) {
        glDeleteBuffers(1, &m->vbo);
        glDeleteVertexArrays(1, &m->vao);
    }
    *m = (bdl_gl_mesh){0};
}
