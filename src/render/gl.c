#include "render/gl.h"

#include <string.h>

#define BDL_GL_DEFINE(type, name) type bdl_gl##name;
BDL_GL_FUNCTIONS(BDL_GL_DEFINE)
#undef BDL_GL_DEFINE

const char *bdl_gl_load(bdl_gl_lookup lookup)
{
    bdl_gl_proc proc;
    // A function pointer cannot be converted to another function pointer type through a cast
    // that -Wpedantic accepts for object pointers; memcpy keeps it well-defined.
#define BDL_GL_FETCH(type, name)                                                                   \
    proc = lookup("gl" #name);                                                                     \
    if (!proc)                                                                                     \
        return "gl" #name;                                                                         \
    memcpy(&bdl_gl##name, &proc, sizeof proc);
    BDL_GL_FUNCTIONS(BDL_GL_FETCH)
#undef BDL_GL_FETCH
    return NULL;
}
