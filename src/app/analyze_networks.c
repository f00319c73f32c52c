// bedlam analyze networks — a contact file of a run ([output] contacts_interval): its force
// networks, coordination and force distribution (analysis/granular.h), force_pdf.csv and
// force_pdf.png.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/granular.h"
#include "app/analyze.h"
#include "app/analyze_files.h"
#include "core/file.h"

/// What a contacts file holds: the contacts, and the centres by particle id (NAN where a
/// particle has no contact).
typedef struct contact_file {
    bdl_contact_rec *c;
    long count, capacity;
    bdl_vec3 *pos;
    long particles, pos_capacity; ///< particles: the largest id + 1
} contact_file;

static void free_contacts(contact_file *cf) { free(cf->c), free(cf->pos); }

/// Room for the centres of particle ids below `top`; 0 when out of memory.
static int grow_positions(contact_file *cf, long top)
{
    if (top <= cf->pos_capacity)
        return 1;
    long cap = cf->pos_capacity ? cf->pos_capacity : 1024;
    while (cap < top)
        cap *= 2;
    bdl_vec3 *p = realloc(cf->pos, (size_t)cap * sizeof *p);
    if (!p)
        return 0;
    for (long k = cf->pos_capacity; k < cap; ++k)
        p[k] = (bdl_vec3){NAN, NAN, NAN};
    cf->pos = p, cf->pos_capacity = cap;
    return 1;
}

/// Adds one line `i,j,species_i,species_j,centre_i,centre_j,overlap,fn` (j < 0: a wall, its
/// contact point as the second centre). -1 on a bad line, 0 out of memory, 1 done.
static int add_contact(contact_file *cf, const char *line)
{
    long i, j;
    int si, sj;
    double xi, yi, zi, xj, yj, zj, ov, fn;
    if (sscanf(line, "%ld,%ld,%d,%d,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &i, &j, &si, &sj, &xi, &yi,
               &zi, &xj, &yj, &zj, &ov, &fn) != 12 ||
        i < 0 || i > 100000000 || j > 100000000)
        return -1;
    const long top = (i > j ? i : j) + 1;
    if (!grow_positions(cf, top))
        return 0;
    cf->particles = top > cf->particles ? top : cf->particles;
    cf->pos[i] = (bdl_vec3){xi, yi, zi};
    if (j >= 0)
        cf->pos[j] = (bdl_vec3){xj, yj, zj};
    if (cf->count == cf->capacity) {
        bdl_contact_rec *c = realloc(cf->c, (size_t)(cf->capacity *= 2) * sizeof *c);
        if (!c)
            return 0;
        cf->c = c;
    }
    cf->c[cf->count++] = (bdl_contact_rec){(int32_t)i, (int32_t)(j < 0 ? -1 : j), fn};
    return 1;
}

/// Reads a contacts file of a run (see output/granular_out.h); prints an error unless BDL_OK.
static bdl_result read_contacts(const char *path, contact_file *cf)
{
    char why[256];
    FILE *f = bdl_open_regular(path, why, sizeof why);
    if (!f) {
        fprintf(stderr, "error: %s %s\n", path, why);
        return BDL_ERR_ARGS;
    }
    *cf = (contact_file){.capacity = 4096};
    cf->c = malloc((size_t)cf->capacity * sizeof *cf->c);
    char line[1024];
    int header = 0, added = cf->c ? 1 : 0;
    while (added > 0 && fgets(line, sizeof line, f)) {
        if (line[0] == '#')
            continue;
        if (header)
            added = add_contact(cf, line);
        else if (!(header = strncmp(line, "i,j,", 4) == 0))
            break;
    }
    fclose(f);
    bdl_result rc = BDL_OK;
    if (added == 0) {
        fprintf(stderr, "error: %s: %s\n", path, bdl_result_text(rc = BDL_ERR_NOMEM));
    } else if (added < 0) {
        fprintf(stderr, "error: %s: bad contact line: %s", path, line);
        rc = BDL_ERR_ARGS;
    } else if (!header || !cf->pos) { // an empty list has no centres either
        fprintf(stderr, "error: %s: not a contacts file of a run (no 'i,j,...' header)\n", path);
        rc = BDL_ERR_ARGS;
    }
    if (rc != BDL_OK)
        free_contacts(cf);
    return rc;
}

/// What the contacts give: their forces, the particles' coordination, and the networks of all
/// the forces and of those above the mean.
typedef struct networks {
    bdl_contact_forces forces;
    bdl_coordination_stats coordination;
    bdl_network_stats all, strong;
} networks;

/// fn gets the positive pair forces (room for every contact).
static bdl_result find_networks(const contact_file *cf, double *fn, networks *nw)
{
    const long n = cf->particles;
    uint8_t *z = calloc((size_t)(n > 0 ? n : 1), 1);
    if (!z)
        return BDL_ERR_NOMEM;
    nw->forces = bdl_contact_forces_of(cf->c, cf->count, fn, z);
    nw->coordination = bdl_coordination(z, n);
    free(z);
    bdl_result rc = bdl_force_networks(n, cf->c, cf->count, 0.0, cf->pos, NULL, &nw->all);
    if (rc == BDL_OK)
        rc = bdl_force_networks(n, cf->c, cf->count, nw->forces.mean, cf->pos, NULL, &nw->strong);
    return rc;
}

static void print_networks(const char *file, const contact_file *cf, const networks *nw)
{
    const bdl_coordination_stats *cs = &nw->coordination;
    const bdl_network_stats *all = &nw->all;
    printf("%s: %ld contacts (%ld with walls), %ld particle pairs with a normal force, mean force "
           "%.6g N; %ld particles touch another, mean coordination among them %.4f, multi-contact "
           "ratio %.4f\n",
           file, cf->count, nw->forces.walls, nw->forces.pairs, nw->forces.mean, cs->in_contact,
           cs->mean_touching, cs->multi_contact_ratio);
    printf("force networks: %ld; the largest has %ld particles and %ld contacts (mean "
           "coordination %.4f), length %.6g m; the other networks have %ld contacts\n",
           all->networks, all->largest, all->largest_edges, all->largest_mean_z,
           all->largest_length, all->other_edges);
    printf("strong networks (F_n above the mean): %ld; the largest has %ld particles\n",
           nw->strong.networks, nw->strong.largest);
}

static bdl_result write_force_pdf(const char *out, const double *centre, const double *pdf,
                                  int bins, const bdl_force_pdf_fit *fit)
{
    char path[1300];
    snprintf(path, sizeof path, "%s/force_pdf.csv", out);
    bdl_atomic_file af;
    if (bdl_atomic_open_csv(&af, path, "f,pdf,fit") != BDL_OK)
        return BDL_ERR_OUTPUT_DIR;
    for (int k = 0; k < bins; ++k)
        fprintf(af.file, "%.6g,%.6g,%.6g\n", centre[k], pdf[k], bdl_force_pdf_eval(fit, centre[k]));
    fprintf(af.file, "# a %.6g b %.6g beta %.6g\n", fit->a, fit->b, fit->beta);
    return bdl_atomic_commit(&af);
}

static void plot_force_pdf(const char *out, const bdl_force_pdf_fit *fit)
{
    char path[1300];
    snprintf(path, sizeof path, "%s/force_pdf.gp", out);
    bdl_analyze_plot(path,
                     "set terminal pngcairo size 800,520 font 'DejaVu Sans,11'\n"
                     "set output '%s/force_pdf.png'\nset datafile separator ','\n"
                     "set xlabel 'f = F_n / <F_n>'\nset ylabel 'P(f)'\nset logscale y\n"
                     "set grid\nset key top right\n"
                     "plot '%s/force_pdf.csv' every ::1 using 1:($2 > 0 ? $2 : 1/0) with points "
                     "pt 7 lc rgb '#3060c0' title 'contacts', '' every ::1 using 1:3 with lines "
                     "lw 2 lc rgb '#c03030' title sprintf('a(1-b e^{-f^2}) e^{-{/Symbol b} f}: "
                     "a %%.2f, b %%.2f, {/Symbol b} %%.2f', %.6g, %.6g, %.6g)\n",
                     out, out, fit->a, fit->b, fit->beta);
}

/// The distribution of the n forces fn[] relative to their mean, fitted, written and plotted.
static bdl_result force_pdf(const bdl_analyze_opts *o, const double *fn, long n)
{
    double *centre = malloc((size_t)o->bins * sizeof(double));
    double *pdf = malloc((size_t)o->bins * sizeof(double));
    bdl_force_pdf_fit fit;
    bdl_result rc = centre && pdf ? BDL_OK : BDL_ERR_NOMEM;
    if (rc == BDL_OK && bdl_force_pdf(fn, n, o->bins, o->fmax, centre, pdf, &fit) != BDL_OK) {
        fprintf(stderr, "error: too few forces for a distribution\n");
        rc = BDL_ERR_NO_RESULT;
    } else if (rc == BDL_OK) {
        printf("force distribution of f = F_n/<F_n>: P(f) = a (1 - b exp(-f^2)) exp(-beta f) "
               "with a = %.4f, b = %.4f, beta = %.4f (rms residual %.3g)\n",
               fit.a, fit.b, fit.beta, fit.rms);
        rc = write_force_pdf(o->out, centre, pdf, o->bins, &fit);
        if (rc == BDL_OK && o->plots)
            plot_force_pdf(o->out, &fit);
    }
    free(centre), free(pdf);
    return rc;
}

bdl_result bdl_analyze_networks(const bdl_analyze_opts *o)
{
    contact_file cf;
    bdl_result rc = read_contacts(o->run, &cf);
    if (rc != BDL_OK)
        return rc;
    double *fn = malloc((size_t)(cf.count > 0 ? cf.count : 1) * sizeof(double));
    networks nw;
    rc = fn ? find_networks(&cf, fn, &nw) : BDL_ERR_NOMEM;
    if (rc == BDL_OK) {
        print_networks(o->run, &cf, &nw);
        rc = force_pdf(o, fn, nw.forces.pairs);
    }
    if (rc == BDL_ERR_NOMEM)
        fprintf(stderr, "error: %s\n", bdl_result_text(rc));
    free_contacts(&cf), free(fn);
    return rc;
}
