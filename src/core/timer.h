// bedlam — wall-clock timing.
#ifndef BDL_TIMER_H
#define BDL_TIMER_H

/// Monotonic wall-clock seconds since an arbitrary origin.
double bdl_wall_seconds(void);
/// Sleeps for `seconds` of wall time.
void bdl_sleep(double seconds);

#endif
