// bedlam — analyses of a granular state: coordination, bed height, mixing (Lacey), force
// networks and the distribution of contact forces.
//
// Each takes plain arrays (positions, per-particle counts, a contact list), so it serves a live
// run (diagnostics), a contacts file written by one (bedlam analyze) and constructed test inputs
// alike.
#ifndef BDL_GRANULAR_H
#define BDL_GRANULAR_H

#include <stdint.h>

#include "core/error.h"
#include "core/vec3.h"

/// Coordination from per-particle contact counts: the mean (contacts per particle, over all n),
/// and the multi-contact ratio, particles with two or more contacts over particles with at least
/// one (Sun 2007, fig. 7.11 caption); 0 when no particle touches another.
typedef struct bdl_coordination_stats {
    double mean;
    double multi_contact_ratio;
    long in_contact;      ///< particles with at least one contact
    double mean_touching; ///< contacts per particle over those with at least one (0 when none)
} bdl_coordination_stats;

bdl_coordination_stats bdl_coordination(const uint8_t *count, long n);

/// The height below which the fraction q of the n values lies (the value of rank floor(q (n-1))
/// in ascending order); sorts h in place. NAN for n = 0.
double bdl_height_quantile(double *h, long n, double q);

/// Lacey's mixing index of species A among the particles (is_a[i] != 0 for A) on a grid of
/// cells[0] x cells[1] x cells[2] equal cells over the box lo..hi: M = (s0^2 - s^2)/(s0^2 - sr^2)
/// with p the number fraction of A, s0^2 = p(1-p) (fully segregated), sr^2 = p(1-p)/nbar (fully
/// random, nbar the mean count of the cells used) and s^2 the mean squared deviation of the cells'
/// fractions of A from p, each cell weighted by its particle count, over the cells holding at
/// least `min_count` particles (p too is taken over those). Weighted, a fully segregated bed gives
/// M = 0 even when the species' cells hold different numbers of particles. 0 means
/// segregated, 1 random. A grid of columns (cells[vertical] = 1) measures horizontal segregation
/// only, one of layers vertical segregation only. NAN when fewer than two cells qualify, when
/// there is only one species, or when nbar <= 1.
double bdl_lacey(const bdl_vec3 *pos, const uint8_t *is_a, long n, bdl_vec3 lo, bdl_vec3 hi,
                 const int cells[3], long min_count);

/// One contact between particles i and j (j < 0: a wall) with normal force fn [N].
typedef struct bdl_contact_rec {
    int32_t i, j;
    double fn;
} bdl_contact_rec;

/// The normal forces of a contact list: the contacts with walls, the particle pairs that press
/// on each other (fn > 0) and their mean force [N] (0 when none).
typedef struct bdl_contact_forces {
    long walls;
    long pairs;
    double mean;
} bdl_contact_forces;

/// Counts the contacts c[0..nc): fn[] gets the positive pair forces in the list's order (room
/// for nc), count[] (one per particle id, zeroed by the caller) each particle's pair contacts with
/// a positive force, at most 255, as bdl_coordination takes them.
bdl_contact_forces bdl_contact_forces_of(const bdl_contact_rec *c, long nc, double *fn,
                                         uint8_t *count);

/// Force networks (Sun 2007, ch. 6): sets of particles each in contact, with a nonzero normal
/// force, with at least one other of the set: the connected components of the graph of the
/// particle-particle contacts with fn > threshold. Wall contacts are not edges.
typedef struct bdl_network_stats {
    long networks;         ///< components with at least two particles
    long largest;          ///< particles in the largest
    long largest_edges;    ///< contacts within the largest
    double largest_mean_z; ///< 2 edges / particles of the largest: its mean coordination
    double largest_length; ///< largest distance between two of its particle centres [m]
    long other_edges;      ///< contacts in all the other networks
} bdl_network_stats;

/// Labels each of the n particles with its network (label[i] = index of the network's smallest
/// particle; an isolated particle is its own label) when `label` is not NULL, and fills *out.
/// `pos` (may be NULL) gives the length scale, by checking every pair of the largest network.
bdl_result bdl_force_networks(long n, const bdl_contact_rec *c, long nc, double threshold,
                              const bdl_vec3 *pos, int32_t *label, bdl_network_stats *out);

/// Sun's fit of the distribution of f = F_n / <F_n> (eq. 6.11, after Mueth et al. 1998):
/// P(f) = a (1 - b exp(-f^2)) exp(-beta f).
typedef struct bdl_force_pdf_fit {
    double a, b, beta;
    double rms; ///< root-mean-square residual of the fitted histogram
} bdl_force_pdf_fit;

/// Histogram of f = fn/mean(fn) for fn > 0 in `bins` bins over [0, fmax] (density: integrates to
/// the fraction of forces below fmax) into centre[] and pdf[] (both `bins` long), and the fit of
/// P(f) to it, by least squares: for each beta on a fine grid a and a b are linear, the best beta
/// is refined by golden section. BDL_ERR_ARGS with fewer than 10 positive forces.
bdl_result bdl_force_pdf(const double *fn, long n, int bins, double fmax, double *centre,
                         double *pdf, bdl_force_pdf_fit *fit);

/// P(f) of the fit.
double bdl_force_pdf_eval(const bdl_force_pdf_fit *fit, double f);

/// Running sums over the axes u of rods (unit vectors; the sign of an axis does not matter):
/// their count, the sum of |u . up| and of the products u_a u_b (xx yy zz xy xz yz). Sums of
/// blocks add with bdl_orientation_merge, so a parallel sum in fixed blocks is deterministic.
typedef struct bdl_orientation_sums {
    double n, abs_cos, uu[6];
} bdl_orientation_sums;

void bdl_orientation_add(bdl_orientation_sums *s, bdl_vec3 u, bdl_vec3 up);
void bdl_orientation_merge(bdl_orientation_sums *into, const bdl_orientation_sums *s);

/// Mean |cos| of the angle between the axes and `up`: 1 all upright, 1/2 isotropic, 0 all
/// lying flat; NAN for no axes.
double bdl_orientation_vertical(const bdl_orientation_sums *s);

/// The nematic order parameter S, the largest eigenvalue of Q = <3/2 u u - 1/2 I>: 1 all
/// parallel, 0 isotropic, 1/4 spread evenly over directions within a plane (a bed of rods lying
/// flat with no preferred heading); NAN for no axes.
double bdl_orientation_order(const bdl_orientation_sums *s);

/// The surface of a settled bed from its solids-fraction profile. Each particle k spreads its
/// volume vol[k] evenly over its vertical extent [lo[k], hi[k]] (a sphere: its centre -/+ r; a
/// rod: from its lower to its upper tip, -/+ r), over layers of thickness dz from z = 0 on a base
/// of the given area. The bulk fraction is the mean over the layers between 20 % and 60 % of the
/// highest point; the surface is the height at which the profile, scanned down from the top,
/// first reaches half the bulk fraction (linear between layer centres): where a camera at the
/// front wall sees the bed end.
typedef struct bdl_bed_surface {
    double height; ///< [m]
    double bulk;   ///< solids fraction below the surface
    double top;    ///< highest point of any particle [m]
    long layers;   ///< of the profile
} bdl_bed_surface;

bdl_result bdl_bed_surface_of(const double *lo, const double *hi, const double *vol, long n,
                              double area, double dz, bdl_bed_surface *out);

#endif
