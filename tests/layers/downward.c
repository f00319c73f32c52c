// The control beside upward.c: the same include path compiles a solver-layer include.
#include "dem/particles.h"
#include "world/world.h"
