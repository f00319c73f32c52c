// bedlam analyze — shared pieces of the analysis subcommands.
#ifndef BDL_ANALYZE_H
#define BDL_ANALYZE_H

/// Reads one column of RUN/FILE (a CSV with a header) into a malloc'ed array; prints an error
/// and returns 0 when it is missing or empty.
int bdl_analyze_read_column(const char *run, const char *file, const char *column, double **out,
                            long *n);

/// Runs gnuplot on a script, then deletes the script; warns when gnuplot is missing.
void bdl_analyze_gnuplot(const char *script_path);

typedef struct bdl_phase_opts {
    const char *file, *column, *out;
    double period, start, below;
    long from_cycle, to_cycle;
    int bins, plots;
} bdl_phase_opts;

/// `analyze phase`: the column folded over the vibration cycle.
bdl_result bdl_analyze_phase(const char *run, const bdl_phase_opts *o);

/// `analyze networks`: force networks and the force distribution of a contact file.
bdl_result bdl_analyze_networks(const char *file, const char *out, int bins, double fmax,
                                int plots);

/// `analyze profile`: the run's profile.csv (solids fraction of each gas cell layer) averaged
/// over [from, to].
bdl_result bdl_analyze_profile(const char *run, const char *out, double from, double to, int plots);

#endif
