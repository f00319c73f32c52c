// bedlam analyze — the analyses of a finished run, one function each, and the options they share.
// cmd_analyze.c parses the command line and calls them; the arithmetic is in analysis/.
#ifndef BDL_ANALYZE_H
#define BDL_ANALYZE_H

#include "core/error.h"

/// Most run folders `bedlam analyze rheology` takes at once.
#define BDL_ANALYZE_RUNS_MAX 256

typedef struct bdl_analyze_opts {
    const char *what;   ///< the analysis: sweep, spectrum, mean, phase, profile, networks or
                        ///< orientation
    const char *run;    ///< the run folder (networks: the contact file)
    const char *out;    ///< the folder the files go to
    const char *file;   ///< the run's CSV file (spectrum, mean, phase)
    const char *column; ///< its column
    double from, to;    ///< time window [s]
    double fmin, fmax;  ///< spectrum: band of the dominant frequency [Hz]; networks: fmax is F
    double period;      ///< phase: of the cycle [s]
    double start;       ///< phase: time the first cycle starts [s]
    double below;       ///< phase: threshold of the intervals reported (NAN: none)
    long from_cycle, to_cycle;
    int bins;        ///< phase bins, or force bins of networks
    int segments;    ///< spectrum: Welch's pieces, half overlapping (1: one periodogram)
    int plots;       ///< run gnuplot
    int by_velocity; ///< orientation: one PDF per stage of the inlet velocity
    double max_step; ///< ptv: longest link [px] (0: half a rod length)
    const char *fit; ///< dia: a calibrate fit.json, for the mass flux (NULL: none)
    double density;  ///< dia: the particles' density with --fit [kg/m^3] (NAN: not given)
    double height;   ///< dia: height of the mass-flux profile [m]
    double cell;     ///< fields: cell size [m] (0: three mean diameters)
    /// rheology: the run folders (runs[0] is `run`), and the spheres' restitution for Lun et al.
    /// (NAN: none)
    const char *runs[BDL_ANALYZE_RUNS_MAX];
    int run_count;
    double restitution;
    double jamming;   ///< rheology: the exponent of the fit to the distance to jamming (0: none)
    double amplitude; ///< rheology: the jamming law's A held fixed (0: fitted with nu_cr)
    double stiffness; ///< rheology: k_n of the soft dense branch (0: its inertial limit only)
    double a2;        ///< rheology: the soft dense branch's a2 (Mahajan 2019, eq. 6.3)
    double damping;   ///< rheology: the runs' background damping b [1/s] for Grad's limit (0: none)
} bdl_analyze_opts;

bdl_result bdl_analyze_sweep(const bdl_analyze_opts *o);
bdl_result bdl_analyze_spectrum(const bdl_analyze_opts *o);
bdl_result bdl_analyze_mean(const bdl_analyze_opts *o);
bdl_result bdl_analyze_phase(const bdl_analyze_opts *o);
bdl_result bdl_analyze_profile(const bdl_analyze_opts *o);
/// Time-averaged solids fraction and velocity on a grid, from the run's particle files.
bdl_result bdl_analyze_fields(const bdl_analyze_opts *o);
bdl_result bdl_analyze_networks(const bdl_analyze_opts *o);
/// A synthetic camera's folder (RUN/dia/NAME): the image-analysis chain against the truth.
bdl_result bdl_analyze_dia(const bdl_analyze_opts *o);
bdl_result bdl_analyze_orientation(const bdl_analyze_opts *o);
/// A high-speed synthetic camera's folder: PTV tracks and coordination numbers against the truth.
bdl_result bdl_analyze_ptv(const bdl_analyze_opts *o);
/// Shear cells' rheology.csv averaged over their steady part, one row per run.
bdl_result bdl_analyze_rheology(const bdl_analyze_opts *o);

#endif
