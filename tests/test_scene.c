// Scene reading: a full scene with every field checked, the defaults, and a table of malformed
// scenes that must each fail with the right key and line in a one-line message.
#define _POSIX_C_SOURCE 200809L // mkdtemp for the file-loading test

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "scene/scene.h"

static const double pi = 3.14159265358979323846;

static const char *const full_scene =
    "# A scene that sets nearly every key.\n"
    "[run]\n"
    "dt = 1e-6            ; explicit step\n"
    "dt_fraction = 0.05\n"
    "end_time = 0.5       # s\n"
    "gravity = 0 0 -9.81\n"
    "seed = 42\n"
    "threads = 4\n"
    "\n"
    "[domain]\n"
    "min = 0 0 0\n"
    "max = 0.1 0.1 0.2\n"
    "periodic = x y\n"
    "\n"
    "[contact]\n"
    "law = hertz\n"
    "damping = closed_form\n"
    "rolling = constant\n"
    "skin = 0.2\n"
    "\n"
    "[species glass_beads_of_soda_lime]   ; soda-lime beads\n"
    "diameter = 0.002\n"
    "distribution = normal\n"
    "diameter_std = 0.0001\n"
    "density = 2500\n"
    "youngs_modulus = 5e7\n"
    "poisson_ratio = 0.3\n"
    "restitution = 0.9\n"
    "friction = 0.5\n"
    "rolling_friction = 0.01\n"
    "background_damping = 0.5\n"
    "tangential_damping_ratio = 0.2\n"
    "\n"
    "[species steel_balls_with_a_long_name]\n"
    "diameter = 0.003\n"
    "distribution = uniform\n"
    "diameter_min = 0.0025\n"
    "diameter_max = 0.0035\n"
    "density = 7800\n"
    "youngs_modulus = 2e8\n"
    "stiffness = 1e4\n"
    "tangential_stiffness = 3e3\n"
    "restitution = 0.8\n"
    "\n"
    "[pair steel_balls_with_a_long_name glass_beads_of_soda_lime]\n"
    "restitution = 0.7\n"
    "friction = 0.3\n"
    "\n"
    "[wall floor]\n"
    "type = plane\n"
    "point = 0 0 0\n"
    "normal = 0 0 2\n"
    "motion = vibrate\n"
    "frequency = 50\n"
    "gamma = 2\n"
    "phase = 0.5\n"
    "friction = 0.4\n"
    "\n"
    "[wall drum]\n"
    "type = cylinder\n"
    "point = 0.05 0.05 0\n"
    "axis = 0 0 3\n"
    "radius = 0.05\n"
    "\n"
    "[wall bin]\n"
    "type = box\n"
    "min = 0 0 0\n"
    "max = 0.1 0.1 0.2\n"
    "motion = vibrate\n"
    "direction = 1 0 0\n"
    "frequency = 20\n"
    "amplitude = 0.001\n"
    "\n"
    "[create bed]\n"
    "type = random\n"
    "species = glass_beads_of_soda_lime\n"
    "region_min = 0 0 0\n"
    "region_max = 0.1 0.1 0.05\n"
    "volume_fraction = 0.3\n"
    "velocity_jitter = 0.01\n"
    "\n"
    "[create rain]\n"
    "type = pour\n"
    "species = steel_balls_with_a_long_name\n"
    "region_min = 0 0 0.15\n"
    "region_max = 0.1 0.1 0.2\n"
    "count = 1000\n"
    "rate = 5000\n"
    "start_time = 0.1\n"
    "velocity = 0 0 -1\n"
    "\n"
    "[create grid]\n"
    "type = lattice\n"
    "species = glass_beads_of_soda_lime\n"
    "region_min = 0 0 0.05\n"
    "region_max = 0.1 0.1 0.1\n"
    "spacing = 0.0025\n"
    "\n"
    "[create loaded]\n"
    "type = file\n"
    "species = glass_beads_of_soda_lime\n"
    "file = check.h\n"
    "\n"
    "[output]\n"
    "diagnostics_interval = 0.01\n"
    "vtk_interval = 0.05\n"
    "checkpoint_interval = 0.25\n"
    "progress_interval = 2\n"
    "\n"
    "[guards]\n"
    "max_overlap = 0.1\n"
    "dt_refuse = 0.3\n"
    "dt_warn = 0.1\n"
    "energy_growth = 0.1\n"
    "check_interval = 50\n";

static void test_full_scene(void)
{
    static bdl_scene scene;
    bdl_scene_error err = {{0}};
    bdl_result r = bdl_scene_load_string(full_scene, "full.ini", NULL, 0, &scene, &err);
    CHECK_MSG(r == BDL_OK, "%s", err.message);
    if (r != BDL_OK)
        return;
    CHECK(strcmp(scene.path, "") == 0);
    CHECK(strcmp(scene.dir, ".") == 0);
    CHECK_CLOSE(scene.dt, 1e-6, 1e-15);
    CHECK_CLOSE(scene.dt_fraction, 0.05, 1e-15);
    CHECK_CLOSE(scene.end_time, 0.5, 1e-15);
    CHECK_CLOSE(scene.gravity.z, -9.81, 1e-15);
    CHECK(scene.gravity.x == 0.0 && scene.gravity.y == 0.0);
    CHECK(scene.seed == 42);
    CHECK(scene.threads == 4);
    CHECK(scene.domain_max.x == 0.1 && scene.domain_max.z == 0.2 && scene.domain_min.y == 0.0);
    CHECK(scene.periodic[0] == 1 && scene.periodic[1] == 1 && scene.periodic[2] == 0);
    CHECK(scene.law == BDL_LAW_HERTZ);
    CHECK(scene.damping == BDL_DAMPING_CLOSED_FORM);
    CHECK(scene.rolling == BDL_ROLLING_CONSTANT);
    CHECK_CLOSE(scene.skin, 0.2, 1e-15);

    CHECK(scene.species_count == 2);
    const bdl_species_def *glass = &scene.species[0];
    CHECK(strcmp(glass->name, "glass_beads_of_soda_lime") == 0);
    CHECK(scene.line.species[0] == 21);
    CHECK(glass->size_dist == BDL_SIZE_NORMAL);
    CHECK_CLOSE(glass->diameter, 0.002, 1e-15);
    CHECK_CLOSE(glass->diameter_std, 0.0001, 1e-15);
    CHECK_CLOSE(glass->diameter_min, 0.0017, 1e-12); // diameter - 3 std
    CHECK_CLOSE(glass->diameter_max, 0.0023, 1e-12); // diameter + 3 std
    CHECK_CLOSE(glass->density, 2500, 1e-15);
    CHECK_CLOSE(glass->background_damping, 0.5, 1e-15);
    CHECK_CLOSE(glass->material.youngs_modulus, 5e7, 1e-15);
    CHECK_CLOSE(glass->material.poisson_ratio, 0.3, 1e-15);
    CHECK(glass->material.stiffness < 0);
    CHECK(glass->material.tangential_stiffness < 0);
    CHECK_CLOSE(glass->material.restitution, 0.9, 1e-15);
    CHECK_CLOSE(glass->material.tangential_damping_ratio, 0.2, 1e-15);
    CHECK_CLOSE(glass->material.friction, 0.5, 1e-15);
    CHECK_CLOSE(glass->material.rolling_friction, 0.01, 1e-15);
    const bdl_species_def *steel = &scene.species[1];
    CHECK(strcmp(steel->name, "steel_balls_with_a_long_name") == 0);
    CHECK(steel->size_dist == BDL_SIZE_UNIFORM);
    CHECK_CLOSE(steel->diameter_min, 0.0025, 1e-15);
    CHECK_CLOSE(steel->diameter_max, 0.0035, 1e-15);
    CHECK_CLOSE(steel->material.stiffness, 1e4, 1e-15);
    CHECK_CLOSE(steel->material.tangential_stiffness, 3e3, 1e-15);
    CHECK_CLOSE(steel->material.poisson_ratio, 0.25, 1e-15);
    CHECK(steel->material.friction == 0.0 && steel->background_damping == 0.0);

    CHECK(scene.pair_count == 1);
    const bdl_pair_def *pair = &scene.pairs[0];
    CHECK(pair->species_a == 1 && pair->species_b == 0);
    CHECK(pair->has_restitution && pair->has_friction);
    CHECK(!pair->has_rolling_friction && !pair->has_stiffness);
    CHECK_CLOSE(pair->restitution, 0.7, 1e-15);
    CHECK_CLOSE(pair->friction, 0.3, 1e-15);
    CHECK(scene.line.pairs[0] == 45);

    CHECK(scene.wall_count == 3);
    const bdl_wall_def *floor_wall = &scene.walls[0];
    CHECK(strcmp(floor_wall->name, "floor") == 0);
    CHECK(floor_wall->kind == BDL_WALL_PLANE);
    CHECK(floor_wall->normal.z == 1.0 && floor_wall->normal.x == 0.0); // normalised
    CHECK(floor_wall->motion == BDL_MOTION_VIBRATE);
    CHECK_CLOSE(floor_wall->frequency, 50, 1e-15);
    double omega = 2.0 * pi * 50.0;
    CHECK_CLOSE(floor_wall->amplitude, 2.0 * 9.81 / (omega * omega), 1e-12);
    CHECK_CLOSE(floor_wall->phase, 0.5, 1e-15);
    CHECK(floor_wall->direction.z == 1.0 && floor_wall->direction.x == 0.0);
    CHECK_CLOSE(floor_wall->material.friction, 0.4, 1e-15);
    CHECK(floor_wall->material.restitution < 0 && floor_wall->material.youngs_modulus < 0);
    CHECK(floor_wall->material.poisson_ratio < 0 && floor_wall->material.stiffness < 0);
    CHECK(floor_wall->material.rolling_friction < 0);
    CHECK(floor_wall->material.tangential_damping_ratio < 0);
    CHECK(floor_wall->material.tangential_stiffness < 0);
    const bdl_wall_def *drum = &scene.walls[1];
    CHECK(drum->kind == BDL_WALL_CYLINDER);
    CHECK(drum->normal.z == 1.0);
    CHECK_CLOSE(drum->radius, 0.05, 1e-15);
    CHECK_CLOSE(drum->point.x, 0.05, 1e-15);
    CHECK(drum->motion == BDL_MOTION_NONE);
    const bdl_wall_def *bin = &scene.walls[2];
    CHECK(bin->kind == BDL_WALL_BOX);
    CHECK(bin->box_max.z == 0.2 && bin->box_min.x == 0.0);
    CHECK(bin->direction.x == 1.0 && bin->direction.z == 0.0);
    CHECK_CLOSE(bin->amplitude, 0.001, 1e-15);

    CHECK(scene.create_count == 4);
    const bdl_create_def *bed = &scene.creates[0];
    CHECK(bed->kind == BDL_CREATE_RANDOM && bed->species == 0);
    CHECK(bed->count == -1);
    CHECK_CLOSE(bed->volume_fraction, 0.3, 1e-15);
    CHECK_CLOSE(bed->velocity_jitter, 0.01, 1e-15);
    CHECK(bed->region_max.z == 0.05);
    const bdl_create_def *rain = &scene.creates[1];
    CHECK(rain->kind == BDL_CREATE_POUR && rain->species == 1);
    CHECK(rain->count == 1000);
    CHECK_CLOSE(rain->rate, 5000, 1e-15);
    CHECK_CLOSE(rain->start_time, 0.1, 1e-15);
    CHECK(rain->velocity.z == -1.0);
    const bdl_create_def *grid = &scene.creates[2];
    CHECK(grid->kind == BDL_CREATE_LATTICE && grid->count == -1);
    CHECK_CLOSE(grid->spacing, 0.0025, 1e-15);
    const bdl_create_def *loaded = &scene.creates[3];
    CHECK(loaded->kind == BDL_CREATE_FILE);
    CHECK(strcmp(loaded->file, "check.h") == 0);
    CHECK(strcmp(loaded->name, "loaded") == 0);

    CHECK_CLOSE(scene.output.diagnostics_interval, 0.01, 1e-15);
    CHECK_CLOSE(scene.output.vtk_interval, 0.05, 1e-15);
    CHECK_CLOSE(scene.output.checkpoint_interval, 0.25, 1e-15);
    CHECK_CLOSE(scene.output.progress_interval, 2, 1e-15);
    CHECK_CLOSE(scene.guards.max_overlap, 0.1, 1e-15);
    CHECK_CLOSE(scene.guards.dt_refuse, 0.3, 1e-15);
    CHECK_CLOSE(scene.guards.dt_warn, 0.1, 1e-15);
    CHECK_CLOSE(scene.guards.energy_growth, 0.1, 1e-15);
    CHECK(scene.guards.check_interval == 50);
}

#define MINIMAL                                                                                    \
    "[run]\n"                                                                                      \
    "end_time = 1\n"                                                                               \
    "[domain]\n"                                                                                   \
    "min = 0 0 0\n"                                                                                \
    "max = 1 1 1\n"                                                                                \
    "[species glass]\n"                                                                            \
    "diameter = 0.01\n"                                                                            \
    "density = 2500\n"                                                                             \
    "youngs_modulus = 1e7\n"                                                                       \
    "restitution = 0.5\n"

static void test_defaults(void)
{
    static bdl_scene scene;
    bdl_scene_error err = {{0}};
    const char *text = MINIMAL "[wall w]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\n"
                               "[create c]\ntype = random\ncount = 10\n"
                               "region_min = 0 0 0\nregion_max = 1 1 1\n"
                               "[create l]\ntype = lattice\nregion_min = 0 0 0\n"
                               "region_max = 1 1 1\n";
    bdl_result r = bdl_scene_load_string(text, "minimal.ini", NULL, 0, &scene, &err);
    CHECK_MSG(r == BDL_OK, "%s", err.message);
    if (r != BDL_OK)
        return;
    CHECK(scene.dt == 0.0);
    CHECK_CLOSE(scene.dt_fraction, 0.02, 1e-15);
    CHECK(scene.gravity.x == 0.0 && scene.gravity.y == 0.0 && scene.gravity.z == -9.81);
    CHECK(scene.seed == 1 && scene.threads == 0);
    CHECK(!scene.periodic[0] && !scene.periodic[1] && !scene.periodic[2]);
    CHECK(scene.law == BDL_LAW_HERTZ && scene.damping == BDL_DAMPING_EXACT);
    CHECK(scene.rolling == BDL_ROLLING_NONE);
    CHECK_CLOSE(scene.skin, 0.1, 1e-15);
    const bdl_species_def *sp = &scene.species[0];
    CHECK(sp->size_dist == BDL_SIZE_SINGLE);
    CHECK(sp->diameter_min == 0.01 && sp->diameter_max == 0.01);
    CHECK_CLOSE(sp->material.poisson_ratio, 0.25, 1e-15);
    CHECK(sp->material.stiffness < 0 && sp->material.tangential_stiffness < 0);
    CHECK(sp->material.friction == 0 && sp->material.rolling_friction == 0);
    CHECK(sp->material.tangential_damping_ratio == 0 && sp->background_damping == 0);
    const bdl_wall_def *w = &scene.walls[0];
    CHECK(w->motion == BDL_MOTION_NONE && w->direction.z == 1.0 && w->phase == 0.0);
    CHECK(w->material.youngs_modulus == -1 && w->material.friction == -1);
    CHECK(scene.creates[0].species == 0 && scene.creates[0].count == 10);
    CHECK(scene.creates[0].volume_fraction < 0);
    CHECK(scene.creates[0].velocity_jitter == 0 && scene.creates[0].velocity.z == 0);
    CHECK(scene.creates[1].count == -1 && scene.creates[1].spacing < 0);
    CHECK_CLOSE(scene.output.diagnostics_interval, 1e-3, 1e-15);
    CHECK(scene.output.vtk_interval == 0 && scene.output.checkpoint_interval == 0);
    CHECK(scene.output.progress_interval == 1);
    CHECK_CLOSE(scene.guards.max_overlap, 0.25, 1e-15);
    CHECK_CLOSE(scene.guards.dt_refuse, 0.2, 1e-15);
    CHECK_CLOSE(scene.guards.dt_warn, 0.05, 1e-15);
    CHECK_CLOSE(scene.guards.energy_growth, 0.05, 1e-15);
    CHECK(scene.guards.check_interval == 100);

    // bdl_scene_defaults alone: the same singleton defaults, no sections.
    static bdl_scene empty;
    bdl_scene_defaults(&empty);
    CHECK(empty.species_count == 0 && empty.wall_count == 0 && empty.create_count == 0);
    CHECK(empty.law == BDL_LAW_HERTZ && empty.guards.check_interval == 100);
    CHECK(strcmp(empty.dir, ".") == 0);
}

static void test_overrides_and_syntax(void)
{
    static bdl_scene scene;
    bdl_scene_error err = {{0}};
    // CRLF line ends, a byte-order mark, indented keys, inline comments, ':' separators.
    const char *text = "\xEF\xBB\xBF[run]\r\n  end_time: 2 ; two seconds\r\n[domain]\r\n"
                       "min = -1 -1 -1\r\nmax = 1 1 1 # box\r\n[species glass] # beads\r\n"
                       "diameter = 1e-2\r\ndensity = 2.5e3\r\nyoungs_modulus = 1E7\r\n"
                       "restitution = 0.5\r\n[pair glass glass]\r\nfriction = 0.2\r\n";
    const char *overrides[] = {"run.end_time=3",
                               "species.glass.density = 1000",
                               "contact.law=linear",
                               "species.glass.stiffness=1e4",
                               "pair.glass.glass.stiffness=2e4",
                               "domain.periodic=z",
                               "run.seed=18446744073709551615",
                               "guards.check_interval=1e3"};
    bdl_result r = bdl_scene_load_string(text, "crlf.ini", overrides, 8, &scene, &err);
    CHECK_MSG(r == BDL_OK, "%s", err.message);
    if (r != BDL_OK)
        return;
    CHECK(scene.end_time == 3.0);
    CHECK(scene.species[0].density == 1000.0);
    CHECK(scene.law == BDL_LAW_LINEAR);
    CHECK(scene.species[0].material.stiffness == 1e4);
    CHECK(scene.pairs[0].has_stiffness && scene.pairs[0].stiffness == 2e4);
    CHECK(scene.pairs[0].species_a == 0 && scene.pairs[0].species_b == 0);
    CHECK(!scene.periodic[0] && scene.periodic[2]);
    CHECK(scene.seed == 18446744073709551615ull);
    CHECK(scene.guards.check_interval == 1000);
    CHECK(scene.domain_min.x == -1.0);
}

static int contains(const char *haystack, const char *needle)
{
    return strstr(haystack, needle) != NULL;
}

static void test_file_loading(void)
{
    static bdl_scene scene;
    bdl_scene_error err = {{0}};
    char dir[] = "/tmp/bdl_test_scene_XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK_MSG(0, "mkdtemp failed");
        return;
    }
    char scene_path[256], csv_path[256];
    snprintf(scene_path, sizeof scene_path, "%s/scene.ini", dir);
    snprintf(csv_path, sizeof csv_path, "%s/points.csv", dir);
    FILE *f = fopen(csv_path, "w");
    CHECK(f != NULL);
    if (f) {
        fputs("0.5,0.5,0.5\n", f);
        fclose(f);
    }
    f = fopen(scene_path, "w");
    CHECK(f != NULL);
    if (f) {
        fputs(MINIMAL "[create from_file]\ntype = file\nfile = points.csv\n", f);
        fclose(f);
    }
    bdl_result r = bdl_scene_load(scene_path, NULL, 0, &scene, &err);
    CHECK_MSG(r == BDL_OK, "%s", err.message);
    CHECK(strcmp(scene.path, scene_path) == 0);
    CHECK(strcmp(scene.dir, dir) == 0);
    CHECK_MSG(strcmp(scene.creates[0].file, csv_path) == 0, "%s", scene.creates[0].file);

    // A bad value in a file names the file and the line.
    const char *set[] = {"create.from_file.velocity_jitter=-1"};
    r = bdl_scene_load(scene_path, set, 1, &scene, &err);
    CHECK(r == BDL_ERR_SCENE && contains(err.message, "--set:"));
    remove(csv_path);
    r = bdl_scene_load(scene_path, NULL, 0, &scene, &err);
    CHECK_MSG(r == BDL_ERR_SCENE && contains(err.message, "scene.ini:13:") &&
                  contains(err.message, "points.csv"),
              "%s", err.message);
    remove(scene_path);
    rmdir(dir);
    r = bdl_scene_load(scene_path, NULL, 0, &scene, &err);
    CHECK(r == BDL_ERR_SCENE && contains(err.message, "scene.ini"));
}

typedef struct bad_scene {
    const char *text;
    const char *where;    ///< "bad.ini:LINE:" or "--set:"
    const char *key;      ///< must appear in the message
    const char *also;     ///< a further fragment that must appear, or NULL
    const char *override; ///< one --set string, or NULL
} bad_scene;

#define SPECIES_B(extra)                                                                           \
    "[species b]\ndiameter = 0.01\ndensity = 1000\nyoungs_modulus = 1e7\nrestitution = "           \
    "0.5\n" extra
#define PLANE "[wall w]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\n"
#define DIA                                                                                        \
    "[camera c]\nkind = dia\nposition = 0 -0.3 0\ntarget = 0 0 0\npixel_size = 1e-4\n"             \
    "interval = 0.01\n"

static const bad_scene bad_scenes[] = {
    {MINIMAL "densty = 3\n", "bad.ini:11:", "densty", "did you mean 'density'?", NULL},
    {MINIMAL "[species bad]\ndiameter = -0.01\n", "bad.ini:12:", "diameter", "> 0 (m)", NULL},
    {MINIMAL "[species bad]\nrestitution = 1.5\n", "bad.ini:12:", "restitution", "(0, 1]", NULL},
    {MINIMAL "[species bad]\ndensity = nan\n", "bad.ini:12:", "density", "finite", NULL},
    {"[run]\nend_time = inf\n", "bad.ini:2:", "end_time", "finite", NULL},
    {MINIMAL "[species bad]\ndiameter = 1.0e-3x\n", "bad.ini:12:", "diameter", "'x'", NULL},
    {MINIMAL "[contact]\nlaw = hertzz\n", "bad.ini:12:", "law", "did you mean 'hertz'?", NULL},
    {MINIMAL "[contact]\nlaw = spring\n", "bad.ini:12:", "law", "allowed: linear, hertz", NULL},
    {"[run]\ndt = 1e-6\n[domain]\nmin = 0 0 0\nmax = 1 1 1\n"
     "[species a]\ndiameter = 1\ndensity = 1\nyoungs_modulus = 1\nrestitution = 1\n",
     "bad.ini:1:", "end_time", "missing required key", NULL},
    {"[domain]\nmin = 0 0 0\nmax = 1 1 1\n", "bad.ini:3:", "end_time", "not in the file", NULL},
    {"[run]\nend_time = 1\n[domain]\nmin = 0 0 0\nmax = 1 1 1\n", "bad.ini:5:", "species",
     "at least one", NULL},
    {"[run]\nend_time = 1\n[species a]\ndiameter = 1\n", "bad.ini:4:", "[domain] min",
     "not in the file", NULL},
    {MINIMAL "[pair glass stel]\nfriction = 0.1\n", "bad.ini:11:", "stel", "unknown species", NULL},
    {MINIMAL PLANE "motion = vibrate\nfrequency = 10\namplitude = 0.001\ngamma = 2\n",
     "bad.ini:18:", "gamma", "exclusive", NULL},
    {MINIMAL PLANE "motion = vibrate\nfrequency = 10\n", "bad.ini:11:", "amplitude", "gamma", NULL},
    {MINIMAL "[species bad]\ndiameter = 0.01\ndiameter = 0.02\n", "bad.ini:13:", "diameter",
     "first at line 12", NULL},
    {"[run]\nend_time = 1\ngravity = 0 -9.81\n", "bad.ini:3:", "gravity", "got 2", NULL},
    {"[run]\nend_time = 1\ngravity = 0 0 -9.81 1\n", "bad.ini:3:", "gravity", "got 4", NULL},
    {MINIMAL "[specie x]\n", "bad.ini:11:", "specie", "did you mean 'species'?", NULL},
    {"[run]\nend_time = 1\n[domain]\nmin = 0 0 0\nmax = 1 1 1\nperiodic = x w\n",
     "bad.ini:6:", "periodic", "'w'", NULL},
    {MINIMAL "[create c]\ntype = file\nfile = no_such_file.csv\n", "bad.ini:13:", "file",
     "no_such_file.csv", NULL},
    {MINIMAL "[create c]\ntype = random\ncount = 10\nregion_min = 0 0 0\nregion_max = 1 1 2\n",
     "bad.ini:15:", "region_max", "outside the domain on the z axis", NULL},
    {MINIMAL "[create c]\ntype = random\ncount = 10\nregion_min = 0 -0.5 0\nregion_max = 1 1 1\n",
     "bad.ini:14:", "region_min", "outside the domain on the y axis", NULL},
    {MINIMAL "[camera]\ngas_field = voidage\n", "bad.ini:12:", "gas_field", "needs a [gas]", NULL},
    {MINIMAL "[gas]\ncells = 2 2 2\nprobe_low = 0.1\nprobe_high = 2\n", "bad.ini:14:", "probe_high",
     "inside the domain", NULL},
    {MINIMAL "[gas]\ncells = 2 2 2\ndistributor_resistance = 100\n",
     "bad.ini:13:", "distributor_resistance", "needs an inlet side", NULL},
    {MINIMAL "[gas]\ncells = 2 2 2\nzmin = inlet\nzmax = outlet\ninlet_velocity = 1\n"
             "jet_velocity = 2\njet_min = 0 0 0\njet_max = 0.5 0.5 0\n"
             "distributor_resistance = 100\n",
     "bad.ini:19:", "distributor_resistance", "no jet", NULL},
    {MINIMAL "[gas]\ncells = 2 2 2\ndistributor_resistance = -5\n",
     "bad.ini:13:", "distributor_resistance", ">= 0 (Pa s/m)", NULL},
    {MINIMAL "[gas]\ncells = 2 2 2\nprobe_low = 0.1\n", "bad.ini:13:", "probe_low", "come in pairs",
     NULL},
    {"[run]\nend_time = 1\n[domain]\nmin = 0 0 0\nmax = 1 1 1\nperiodic = x\n[gas]\n"
     "cells = 4 1 4\npressure_solver = direct\n",
     "bad.ini:9:", "pressure_solver", "no periodic axis of more than one cell", NULL},
    {MINIMAL "[gas]\ncells = 40 40 2\npressure_solver = direct\n", "bad.ini:13:", "pressure_solver",
     "a band of 1600 cells", NULL},
    {MINIMAL "[gas]\ncells = 30 30 1200\npressure_solver = direct\n", "bad.ini:13:",
     "pressure_solver", "a band of 900 cells over 1080000 cells each step, 8.7e+11", NULL},
    {MINIMAL, "--set:", "densty", "did you mean 'density'?", "species.glass.densty=3"},
    {MINIMAL, "--set:", "end_time", "out of range", "run.end_time=-1"},
    {MINIMAL, "--set:", "specis", "did you mean 'species'?", "specis.glass.density=3"},
    {MINIMAL, "--set:", "glas", "did you mean 'glass'?", "species.glas.density=3"},
    {MINIMAL, "--set:", "floor", "no such section", "wall.floor.friction=0.1"},
    {MINIMAL, "--set:", "end_time", "expected", "run.end_time"},
    {"[run]\nendtime = 1\n", "bad.ini:2:", "endtime", "did you mean 'end_time'?", NULL},
    {MINIMAL "[run]\n", "bad.ini:11:", "run", "duplicate section (first at line 1)", NULL},
    {MINIMAL "[species glass]\n", "bad.ini:11:", "glass", "duplicate section", NULL},
    {MINIMAL PLANE "radius = 0.1\n", "bad.ini:15:", "radius", "does not apply for type = plane",
     NULL},
    {MINIMAL "[create c]\ntype = random\ncount = 10\nvolume_fraction = 0.1\n"
             "region_min = 0 0 0\nregion_max = 1 1 1\n",
     "bad.ini:14:", "volume_fraction", "exclusive", NULL},
    {MINIMAL "[wall w]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 0\n", "bad.ini:14:", "normal",
     "zero vector", NULL},
    {MINIMAL "[species s2]\ndiameter = 0.01\n", "bad.ini:11:", "density", "missing required key",
     NULL},
    {MINIMAL "just some words\n", "bad.ini:11:", "just some words", "cannot parse", NULL},
    {MINIMAL "[create c]\ntype = lattice\nspecies = glas\nregion_min = 0 0 0\nregion_max = 1 1 1\n",
     "bad.ini:13:", "species", "did you mean 'glass'?", NULL},
    {MINIMAL SPECIES_B("[create c]\ntype = lattice\nregion_min = 0 0 0\nregion_max = 1 1 1\n"),
     "bad.ini:16:", "species", "the scene has 2 species", NULL},
    {MINIMAL "[species s2]\ndiameter = 0.01\ndistribution = uniform\ndiameter_min = 0.02\n"
             "diameter_max = 0.03\ndensity = 1\nyoungs_modulus = 1\nrestitution = 0.5\n",
     "bad.ini:14:", "diameter_min", "larger than diameter", NULL},
    {MINIMAL "[species s2]\ndiameter = 0.01\ndistribution = uniform\ndensity = 1\n",
     "bad.ini:11:", "diameter_min", "for distribution = uniform", NULL},
    {MINIMAL "[species s2]\ndiameter = 0.01\ndiameter_std = 0.001\n", "bad.ini:13:", "diameter_std",
     "does not apply", NULL},
    {"[run]\nend_time = 1\ngravity = 0 0 0\n[domain]\nmin = 0 0 0\nmax = 1 1 1\n"
     "[species a]\ndiameter = 1\ndensity = 1\nyoungs_modulus = 1\nrestitution = 1\n" PLANE
     "motion = vibrate\nfrequency = 10\ngamma = 1\n",
     "bad.ini:18:", "gamma", "gravity", NULL},
    {MINIMAL "[guards]\ndt_warn = 0.5\n", "bad.ini:12:", "dt_warn", "dt_refuse", NULL},
    {"[run]\nend_time = 1\n[domain]\nmin = 0 0 0\nmax = 1 0 1\n", "bad.ini:5:", "max",
     "on the y axis", NULL},
    {MINIMAL "[contact]\nlaw = linear\n", "bad.ini:6:", "stiffness", "law = linear", NULL},
    {"end_time = 1\n[run]\n", "bad.ini:1:", "end_time", "outside any section", NULL},
    {MINIMAL "[wall b]\ntype = box\nmin = 0 0 0\nmax = 1 1 -1\n", "bad.ini:14:", "max",
     "on the z axis", NULL},
    {"[run]\nend_time = 1\nthreads = 1.5\n", "bad.ini:3:", "threads", "not an integer", NULL},
    {"[run]\nend_time = 1\nthreads = 300\n", "bad.ini:3:", "threads", "[0, 256]", NULL},
    {"[run]\nend_time = 1\nseed = -1\n", "bad.ini:3:", "seed", "out of range", NULL},
    {MINIMAL "[create p]\ntype = pour\ncount = 10\nregion_min = 0 0 0\nregion_max = 1 1 1\n",
     "bad.ini:11:", "rate", "for type = pour", NULL},
    {MINIMAL "[species s2]\npoisson_ratio = 0.5\n", "bad.ini:12:", "poisson_ratio", "(-1, 0.5)",
     NULL},
    {MINIMAL "[wall w\n", "bad.ini:11:", "]", "section header", NULL},
    {MINIMAL "[wall]\n", "bad.ini:11:", "wall", "wall NAME", NULL},
    {MINIMAL "[run now]\n", "bad.ini:11:", "run now", "takes no name", NULL},
    {MINIMAL "[species this_name_is_far_too_long_for_a_species]\n",
     "bad.ini:11:", "this_name_is_far_too_long", "longer than 31", NULL},
    {MINIMAL "[wall w]\ntype = plain\n", "bad.ini:12:", "type", "did you mean 'plane'?", NULL},
    {MINIMAL "[wall w]\ntype = plane\npoint = 0 0 0\n", "bad.ini:11:", "normal", "for type = plane",
     NULL},
    {MINIMAL "[create c]\ntype = lattice\nregion_min = 0 0 0\nregion_max = 1 1 1\n"
             "spacing = 0.005\n",
     "bad.ini:15:", "spacing", "overlap", NULL},
    {MINIMAL "[create c]\ntype = random\nregion_min = 0 0 0\nregion_max = 1 1 1\n",
     "bad.ini:11:", "count", "volume_fraction", NULL},
    {MINIMAL "[create c]\ntype = random\nvolume_fraction = 0.7\n", "bad.ini:13:", "volume_fraction",
     "(0, 0.64]", NULL},
    {MINIMAL "[create c]\ntype = random\ncount = 10\nregion_min = 0 0 0\nregion_max = 1 1 0.005\n",
     "bad.ini:15:", "region_max", "narrower", NULL},
    {MINIMAL "[output]\nvtk_interval = -1\n", "bad.ini:12:", "vtk_interval", ">= 0 (s)", NULL},
    {MINIMAL "[output]\nfields_interval = -0.1\n", "bad.ini:12:", "fields_interval = -0.1",
     ">= 0 (s)", NULL},
    {MINIMAL "[output]\nfields_interval = nan\n", "bad.ini:12:", "fields_interval",
     "not a finite number", NULL},
    {MINIMAL "[output]\nfields_interval = 1e-12\n", "bad.ini:12:", "fields_interval",
     "at most 1e+09 per run", NULL},
    {MINIMAL "[output]\nfields_start = -1\n", "bad.ini:12:", "fields_start = -1", ">= 0 (s)", NULL},
    {MINIMAL "[output]\nfields_cell = 0\n", "bad.ini:12:", "fields_cell = 0", "> 0 (m)", NULL},
    {MINIMAL "[output]\nfields_cell = 1.5\n", "bad.ini:12:", "fields_cell = 1.5",
     "larger than the domain (its largest side is 1 m); allowed: > 0 and <= 1 (m)", NULL},
    {MINIMAL "[output]\nfields_interval = 0.1\nfields_cell = 1e-3\n", "bad.ini:13:",
     "fields_cell = 0.001", "makes about 1e+09 cells over the domain, more than 5e+07", NULL},
    {MINIMAL "[contact]\nskin =\n", "bad.ini:12:", "skin", "missing value", NULL},
    {MINIMAL "[species s2]\nyoungs = 1\n", "bad.ini:12:", "youngs", "'youngs_modulus'", NULL},
    {MINIMAL SPECIES_B("[pair glass b]\n[pair b glass]\n"), "bad.ini:17:", "pair b glass",
     "duplicate section (first at line 16)", NULL},
    {MINIMAL PLANE "poisson_ratio = -0.2\n", "bad.ini:15:", "poisson_ratio", "[0, 0.5)", NULL},
    {MINIMAL DIA "bits = 12\n", "bad.ini:17:", "bits", "8 or 16", NULL},
    {MINIMAL DIA "pair_dt = 0.1\n", "bad.ini:17:", "pair_dt", "shorter than interval", NULL},
    {MINIMAL "[camera c]\nkind = dia\nposition = 0 -1 0\ntarget = 0 -1 0\npixel_size = 1e-4\n"
             "interval = 1\n",
     "bad.ini:14:", "target", "differ from position", NULL},
    {MINIMAL "[camera c]\nkind = dia\nposition = 0 -1 0\ntarget = 0 0 0\npixel_size = 1e-4\n",
     "bad.ini:11:", "interval", "missing required key", NULL},
    {MINIMAL "[camera c]\nkind = camera\n", "bad.ini:12:", "kind", "dia", NULL},
    {MINIMAL, "--set:", "shear_rate", "need periodic = x z", "domain.shear_rate=10"},
    {MINIMAL "[output]\nrheology_margin = 0.5\n", "bad.ini:12:", "rheology_margin",
     "less than the domain's height", NULL},
    {MINIMAL "[wall d]\ntype = disk\npoint = 0 0 0\nnormal = 0 0 1\nradius = 0.1\nperiodic = x\n",
     "bad.ini:16:", "periodic", "not periodic in [domain]", NULL},
};

static void test_bad_scenes(void)
{
    static bdl_scene scene;
    int count = (int)(sizeof bad_scenes / sizeof bad_scenes[0]);
    CHECK(count >= 20);
    for (int i = 0; i < count; ++i) {
        const bad_scene *b = &bad_scenes[i];
        bdl_scene_error err = {{0}};
        const char *overrides[1] = {b->override};
        bdl_result r =
            bdl_scene_load_string(b->text, "bad.ini", overrides, b->override ? 1 : 0, &scene, &err);
        printf("  case %2d: %s\n", i, err.message);
        CHECK_MSG(r == BDL_ERR_SCENE, "case %d accepted", i);
        CHECK_MSG(strncmp(err.message, b->where, strlen(b->where)) == 0,
                  "case %d: expected location '%s' in: %s", i, b->where, err.message);
        CHECK_MSG(contains(err.message, b->key), "case %d: expected key '%s' in: %s", i, b->key,
                  err.message);
        CHECK_MSG(!b->also || contains(err.message, b->also), "case %d: expected '%s' in: %s", i,
                  b->also, err.message);
        CHECK_MSG(!strchr(err.message, '\n'), "case %d: message spans lines", i);
    }
}

static void test_limits(void)
{
    static bdl_scene scene;
    static char text[16384];
    bdl_scene_error err = {{0}};
    snprintf(text, sizeof text, "%s", MINIMAL);
    for (int i = 0; i <= BDL_MAX_WALLS; ++i)
        snprintf(text + strlen(text), sizeof text - strlen(text), "[wall w%d]\ntype = box\n", i);
    bdl_result r = bdl_scene_load_string(text, "many.ini", NULL, 0, &scene, &err);
    CHECK_MSG(r == BDL_ERR_SCENE && contains(err.message, "too many") &&
                  contains(err.message, "many.ini:43:"),
              "%s", err.message);

    // A line longer than the reader accepts is reported, not silently split.
    snprintf(text, sizeof text, "%s[output]\nvtk_interval = 0.1 ", MINIMAL);
    size_t used = strlen(text);
    memset(text + used, ' ', 5000);
    snprintf(text + used + 5000, sizeof text - used - 5000, "\n");
    r = bdl_scene_load_string(text, "long.ini", NULL, 0, &scene, &err);
    CHECK_MSG(r == BDL_ERR_SCENE && contains(err.message, "long.ini:12:"), "%s", err.message);
}

int main(void)
{
    test_full_scene();
    test_defaults();
    test_overrides_and_syntax();
    test_file_loading();
    test_bad_scenes();
    test_limits();
    return bdl_test_summary("test_scene");
}
