// The solver thread: commands apply between steps and are logged with their step; snapshots
// arrive through the triple buffer; a stop ends the loop cleanly.
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "check.h"
#include "scene_util.h"
#include "core/log.h"
#include "run/loop.h"

static const char *const scene_text =
    "[run]\nend_time = 10\n"
    "[domain]\nmin = 0 0 0\nmax = 0.02 0.02 0.05\n"
    "[contact]\nlaw = linear\n"
    "[species s]\ndiameter = 0.002\ndensity = 2500\nstiffness = 1000\nrestitution = 0.5\n"
    "[wall base]\ntype = box\nmin = 0 0 0\nmax = 0.02 0.02 0.05\nmotion = vibrate\n"
    "frequency = 20\namplitude = 0.001\n"
    "[create bed]\ntype = lattice\ncount = 50\nregion_min = 0 0 0.002\nregion_max = 0.02 0.02 "
    "0.02\n";

static void pause_ms(long ms)
{
    struct timespec ts = {ms / 1000, (ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}

static void wait_for_step(bdl_loop *loop, long target)
{
    for (int k = 0; k < 5000; ++k) {
        double t;
        long step, n;
        int finished;
        bdl_loop_progress(loop, &t, &step, &n, &finished);
        if (step >= target || finished)
            return;
        pause_ms(1);
    }
}

static bdl_command command(bdl_command_kind kind, const char *key, double value)
{
    bdl_command c;
    memset(&c, 0, sizeof c);
    c.kind = kind;
    if (key)
        snprintf(c.key, sizeof c.key, "%s", key);
    c.value = value;
    return c;
}

int main(void)
{
    bdl_world *w = bdl_test_world("%s", scene_text);
    FILE *log = tmpfile();
    bdl_log_set_file(log);

    bdl_loop_def def = bdl_default_loop_def();
    def.world = w;
    def.end_time = 10.0;
    def.publish = 1;
    def.publish_interval = 0.0;
    def.start_paused = 1;
    bdl_loop *loop = bdl_loop_start(&def);
    CHECK(loop != NULL);

    // Paused: nothing moves until single steps are asked for.
    pause_ms(50);
    double t;
    long step, n;
    int finished;
    bdl_loop_progress(loop, &t, &step, &n, &finished);
    CHECK(step == 0);
    for (int k = 0; k < 3; ++k) {
        bdl_command c = command(BDL_CMD_STEP, NULL, 0);
        bdl_loop_command(loop, &c);
    }
    wait_for_step(loop, 3);
    pause_ms(50);
    bdl_loop_progress(loop, &t, &step, &n, &finished);
    CHECK_MSG(step == 3, "three single steps gave %ld", step);

    const bdl_snapshot *snap = bdl_loop_acquire(loop);
    CHECK(snap != NULL);
    if (snap) {
        CHECK(snap->count == 50);
        CHECK(snap->step == 3);
    }

    bdl_command set = command(BDL_CMD_SET, "wall.base.amplitude_scale", 2.0);
    bdl_loop_command(loop, &set);
    bdl_command bad = command(BDL_CMD_SET, "wall.nope.amplitude_scale", 2.0);
    bdl_loop_command(loop, &bad);
    bdl_command resume = command(BDL_CMD_RESUME, NULL, 0);
    bdl_loop_command(loop, &resume);
    wait_for_step(loop, 200);
    bdl_command stop = command(BDL_CMD_STOP, NULL, 0);
    bdl_loop_command(loop, &stop);
    CHECK(bdl_loop_join(loop) == BDL_OK);
    bdl_loop_progress(loop, &t, &step, &n, &finished);
    CHECK(finished);
    CHECK(step >= 200 && step < 100000);
    CHECK_CLOSE(w->walls.amplitude[0], 0.002, 1e-12);
    snap = bdl_loop_acquire(loop);
    CHECK(snap && snap->step == w->step);

    // The log names each command with the step it took effect at.
    bdl_log_set_file(NULL);
    rewind(log);
    char line[512], text[8192] = "";
    while (fgets(line, sizeof line, log))
        strncat(text, line, sizeof text - strlen(text) - 1);
    fclose(log);
    printf("%s", text);
    int steps_logged = 0;
    for (const char *q = text; (q = strstr(q, ": command step")) != NULL; ++q)
        ++steps_logged;
    CHECK(strstr(text, "step 0: command step") != NULL);
    CHECK(steps_logged == 3);
    CHECK(strstr(text, "step 3: command set wall.base.amplitude_scale = 2") != NULL);
    CHECK(strstr(text, "unknown parameter 'wall.nope.amplitude_scale'") != NULL);
    CHECK(strstr(text, ": command stop") != NULL);
    bdl_loop_destroy(loop);
    bdl_world_destroy(w);
    return bdl_test_summary("test_loop");
}
