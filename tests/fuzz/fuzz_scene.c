// bedlam — a fuzz harness for the scene reader (libFuzzer).
//
// An input is the text of a scene file. It is read and validated as `bedlam check` reads a file;
// a scene that passes is built into a world (the resource estimate first: the harness lowers
// [guards] max_memory to 3 MB and max_steps to 10^7 so that a valid but large scene is refused
// quickly rather than built) and stepped three times. The reader must end in BDL_OK or in
// BDL_ERR_SCENE with a message naming the file; building must end in BDL_OK or in a refusal with
// a reason. Anything else (a crash, a sanitizer report, a hang, another result) is a finding.
//
// With libFuzzer (clang):
//   CC=clang cmake -S . -B build-fuzz -DBDL_FUZZ=ON && cmake --build build-fuzz --target fuzz_scene
//   build-fuzz/tests/fuzz/fuzz_scene CORPUS scenes tests/scenes -runs=1000000
// Without it, fuzz_scene_replay (any compiler) runs the files it is given, e.g. every scene of the
// repository (the test fuzz_scene_seeds) or a finding to reproduce.
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/file.h"
#include "dem/species.h"
#include "scene/scene.h"
#include "world/world.h"

/// A random fill asking for more than 0.3 of its region: random sequential insertion jams near
/// 0.38 and then spends its whole budget of tries (seconds) before it refuses the scene. Such a
/// fill is not built here: the reader, not the fill, is fuzzed.
static int dense_random_fill(const bdl_scene *scene)
{
    for (int k = 0; k < scene->create_count; ++k) {
        const bdl_create_def *c = &scene->creates[k];
        if (c->kind != BDL_CREATE_RANDOM)
            continue;
        const bdl_vec3 e = bdl_v3_sub(c->region_max, c->region_min);
        const bdl_species_def *sp = &scene->species[c->species];
        const double region = e.x * e.y * e.z;
        const double fraction =
            c->count >= 0 ? (double)c->count * bdl_species_volume(sp, sp->diameter) / region
                          : c->volume_fraction;
        if (!(fraction <= 0.3))
            return 1;
    }
    return 0;
}

/// What became of one input.
typedef enum outcome { REFUSED_SCENE, REFUSED_WORLD, STEPPED, FINDING } outcome;

static outcome run_one(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    if (!text)
        return FINDING;
    memcpy(text, data, size);
    text[size] = '\0';
    static bdl_scene scene; // large; one input at a time
    bdl_scene_error err = {0};
    const bdl_result r = bdl_scene_load_string(text, "fuzz.ini", NULL, 0, &scene, &err);
    free(text);
    if (r != BDL_OK)
        return r == BDL_ERR_SCENE && err.message[0] ? REFUSED_SCENE : FINDING;
    if (dense_random_fill(&scene))
        return REFUSED_WORLD;
    scene.guards.max_memory = 3e6; // about a thousand particles: the reader is what is fuzzed
    scene.guards.max_steps = 1e7;
    bdl_world *w = NULL;
    const bdl_result made = bdl_world_create(&scene, &w, &err);
    if (made != BDL_OK) {
        bdl_world_destroy(w);
        return made == BDL_ERR_NOMEM || err.message[0] ? REFUSED_WORLD : FINDING;
    }
    for (int s = 0; s < 3; ++s)
        bdl_world_step(w);
    bdl_world_destroy(w);
    return STEPPED;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (run_one(data, size) == FINDING)
        abort(); // libFuzzer keeps the input
    return 0;
}

#ifndef BDL_LIBFUZZER
int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: fuzz_scene_replay FILE...\n");
        return 2;
    }
    static const char *const names[] = {"refused (scene)", "refused (world)", "stepped", "FINDING"};
    int findings = 0;
    for (int a = 1; a < argc; ++a) {
        size_t size = 0;
        char *bytes = bdl_read_file(argv[a], &size);
        if (!bytes) {
            fprintf(stderr, "fuzz_scene: cannot read %s\n", argv[a]);
            return 2;
        }
        const outcome o = run_one((const uint8_t *)bytes, size);
        printf("%s: %s\n", argv[a], names[o]);
        findings += o == FINDING;
        free(bytes);
    }
    return findings != 0;
}
#endif
