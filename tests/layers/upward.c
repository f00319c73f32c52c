// A solver-layer source that includes a header of a higher layer: must not compile with the
// solver layer's include path (tests/layers/check_build.cmake).
#include "dem/particles.h"
#include "render/renderer.h"
