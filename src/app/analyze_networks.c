// bedlam analyze networks — a contact file of a run ([output] contacts_interval): its force
// networks, coordination and force distribution (analysis/granular.h), force_pdf.csv and
// force_pdf.png; the spatial correlation of the contact forces, force_correlation.csv; and with
// --file PARTICLES.vtp (the particle file of the same moment) Sun's multi-pass minimum spanning
// trees of the centres against the force networks (analysis/spanning.h; his table 6.2).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/granular.h"
#include "analysis/spanning.h"
#include "app/analyze.h"
#include "app/analyze_files.h"
#include "core/file.h"
#include "io/vtk.h"

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

/// The contacts' force correlation F(r) (eq. 6.12): contacts at the midpoints of their centres,
/// f = F_n / <F_n>, bins of a tenth of the mean centre distance of the contacts out to ten of it.
static bdl_result force_correlation(const bdl_analyze_opts *o, const contact_file *cf, double mean)
{
    enum { BINS = 100 };
    bdl_vec3 *at = malloc((size_t)(cf->count > 0 ? cf->count : 1) * sizeof *at);
    double *f = malloc((size_t)(cf->count > 0 ? cf->count : 1) * sizeof *f);
    double F[BINS], gap = 0.0;
    long pairs[BINS], n = 0;
    bdl_result rc = at && f ? BDL_OK : BDL_ERR_NOMEM;
    for (long k = 0; rc == BDL_OK && k < cf->count; ++k) {
        const bdl_contact_rec *c = &cf->c[k];
        if (c->j < 0 || !(c->fn > 0.0))
            continue;
        at[n] = bdl_v3_scale(bdl_v3_add(cf->pos[c->i], cf->pos[c->j]), 0.5);
        gap += bdl_v3_len(bdl_v3_sub(cf->pos[c->i], cf->pos[c->j]));
        f[n++] = c->fn / mean;
    }
    if (rc == BDL_OK && n > 1) {
        const double d = gap / (double)n, dr = 0.1 * d;
        bdl_force_correlation(n, at, f, BINS, dr, F, pairs);
        char path[1300];
        snprintf(path, sizeof path, "%s/force_correlation.csv", o->out);
        bdl_atomic_file af;
        rc = bdl_atomic_open_csv(&af, path, "r,r_over_d,F,pairs");
        for (int k = 0; rc == BDL_OK && k < BINS; ++k)
            fprintf(af.file, "%.6g,%.4g,%.6g,%ld\n", (k + 0.5) * dr, (k + 0.5) * 0.1, F[k],
                    pairs[k]);
        rc = rc == BDL_OK ? bdl_atomic_commit(&af) : BDL_ERR_OUTPUT_DIR;
        printf("force correlation F(r) of %ld contacts (r in mean contact distances d = %.6g m):",
               n, d);
        for (int r = 1; r <= 5; ++r) // the bins centred on r d: the 10 r - 1 and 10 r ones
            printf(" %d d: %.3f", r, 0.5 * (F[10 * r - 1] + F[10 * r]));
        printf("\n");
    }
    free(at), free(f);
    return rc;
}

/// Particle centres by id from the particle file of the same moment (NaN for ids it lacks).
static bdl_result centres_by_id(const char *path, long *n, bdl_vec3 **pos)
{
    bdl_vtp_file vf;
    char why[300];
    double *x = NULL, *id = NULL;
    bdl_result rc = bdl_vtp_open(path, &vf, why, sizeof why);
    if (rc == BDL_OK)
        rc = bdl_vtp_array(&vf, "Points", 3, &x, why, sizeof why);
    if (rc == BDL_OK)
        rc = bdl_vtp_array(&vf, "id", 1, &id, why, sizeof why);
    long top = 0;
    for (long k = 0; rc == BDL_OK && k < vf.points; ++k)
        top = id[k] >= 0 && id[k] < 1e8 && id[k] + 1 > top ? (long)id[k] + 1 : top;
    *pos = rc == BDL_OK ? malloc((size_t)(top > 0 ? top : 1) * sizeof **pos) : NULL;
    if (rc == BDL_OK && !*pos)
        rc = BDL_ERR_NOMEM;
    for (long k = 0; rc == BDL_OK && k < top; ++k)
        (*pos)[k] = (bdl_vec3){NAN, NAN, NAN};
    for (long k = 0; rc == BDL_OK && k < vf.points; ++k)
        if (id[k] >= 0 && id[k] < (double)top)
            (*pos)[(long)id[k]] = (bdl_vec3){x[3 * k], x[3 * k + 1], x[3 * k + 2]};
    if (rc != BDL_OK)
        fprintf(stderr, "error: %s %s\n", path, why);
    *n = top;
    free(x), free(id);
    if (vf.data)
        bdl_vtp_close(&vf);
    return rc;
}

static int compare_key(const void *a, const void *b)
{
    const int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
    return x < y ? -1 : x > y;
}

/// The key of the pair (i, j) whichever way round, among n particles.
static int64_t pair_key(int32_t i, int32_t j, long n)
{
    return i < j ? (int64_t)i * n + j : (int64_t)j * n + i;
}

/// Sun's table 6.2: the union of 1 to 5 spanning trees of all the centres (edges already chosen
/// lengthened by 1.2 each pass), kept where the two particles touch with a normal force: its
/// largest tree of contacting particles and the others, against the force networks.
static bdl_result spanning_table(const bdl_analyze_opts *o, const contact_file *cf,
                                 const networks *nw)
{
    enum { PASSES = 5 };
    long n = 0, count = 0;
    bdl_vec3 *pos = NULL;
    bdl_result rc = centres_by_id(o->file, &n, &pos);
    bdl_span_edge *e = rc == BDL_OK ? malloc((size_t)(PASSES * n + 1) * sizeof *e) : NULL;
    bdl_contact_rec *kept = rc == BDL_OK ? malloc((size_t)(PASSES * n + 1) * sizeof *kept) : NULL;
    if (rc == BDL_OK && (!e || !kept))
        rc = BDL_ERR_NOMEM;
    if (rc == BDL_OK)
        rc = bdl_spanning_passes(n, pos, PASSES, 1.2, e, &count);
    // The pairs that touch with a normal force, sorted by their key, to look the edges up in.
    const long top = n > cf->particles ? n : cf->particles;
    int64_t *touch = rc == BDL_OK ? malloc((size_t)(cf->count + 1) * sizeof *touch) : NULL;
    long nt = 0;
    if (rc == BDL_OK && !touch)
        rc = BDL_ERR_NOMEM;
    for (long c = 0; rc == BDL_OK && c < cf->count; ++c)
        if (cf->c[c].j >= 0 && cf->c[c].fn > 0.0)
            touch[nt++] = pair_key(cf->c[c].i, cf->c[c].j, top);
    if (rc == BDL_OK)
        qsort(touch, (size_t)nt, sizeof *touch, compare_key);
    printf("| spanning-tree passes | largest tree N_P | its edges | other trees | their edges "
           "|\n|---|---|---|---|---|\n");
    for (int p = 1; rc == BDL_OK && p <= PASSES; ++p) {
        long m = 0;
        for (long k = 0; k < count && e[k].pass <= p; ++k) {
            const int64_t key = pair_key(e[k].i, e[k].j, top);
            if (bsearch(&key, touch, (size_t)nt, sizeof *touch, compare_key))
                kept[m++] = (bdl_contact_rec){e[k].i, e[k].j, 1.0};
        }
        bdl_network_stats s;
        rc = bdl_force_networks(top, kept, m, 0.0, NULL, NULL, &s);
        if (rc == BDL_OK)
            printf("| %d | %ld | %ld | %ld | %ld |\n", p, s.largest, s.largest_edges,
                   s.networks > 0 ? s.networks - 1 : 0, s.other_edges);
    }
    if (rc == BDL_OK)
        printf("| force networks | %ld | %ld | %ld | %ld |\n", nw->all.largest,
               nw->all.largest_edges, nw->all.networks > 0 ? nw->all.networks - 1 : 0,
               nw->all.other_edges);
    free(pos), free(e), free(kept), free(touch);
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
    if (rc == BDL_OK)
        rc = force_correlation(o, &cf, nw.forces.mean);
    if (rc == BDL_OK && o->file)
        rc = spanning_table(o, &cf, &nw);
    if (rc == BDL_ERR_NOMEM)
        fprintf(stderr, "error: %s\n", bdl_result_text(rc));
    free_contacts(&cf), free(fn);
    return rc;
}
