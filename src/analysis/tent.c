// bedlam — tent-kernel reads of a cell field (tent.h), with the coupling's weights.
#include "analysis/tent.h"

#include <math.h>

/// Weights of the centres m = first .. first + count - 1 along axis a (wrapped on a periodic
/// axis), as couple/coupling.c's axis_weights gives them for a cell-centred slot.
static int axis_weights(const bdl_tent_field *f, int a, double x, int *first, double *w)
{
    const int n = f->n[a];
    if (n == 1 && f->periodic[a]) {
        *first = 0, w[0] = 1.0;
        return 1;
    }
    const double reach = f->width[a] / f->h[a];
    double u = (x - f->lo[a]) / f->h[a] - 0.5;
    const double far = 4.0 * (n + BDL_TENT_MAX);
    u = !(u > -far) ? -far : u < far ? u : far;
    int from = (int)ceil(u - reach), to = (int)floor(u + reach);
    if (!f->periodic[a]) {
        from = from < 0 ? 0 : from;
        to = to > n - 1 ? n - 1 : to;
    }
    if (to - from + 1 > BDL_TENT_MAX)
        to = from + BDL_TENT_MAX - 1;
    double sum = 0.0;
    int count = 0;
    for (int m = from; m <= to; ++m) {
        const double wm = fmax(0.0, 1.0 - fabs(m - u) / reach);
        w[count++] = wm;
        sum += wm;
    }
    if (count == 0 || !(sum > 0.0)) { // outside the domain: the nearest centre
        const int m = (int)floor(u + 0.5);
        *first = m < 0 ? 0 : m > n - 1 ? n - 1 : m;
        w[0] = 1.0;
        return 1;
    }
    for (int k = 0; k < count; ++k)
        w[k] /= sum;
    *first = from;
    return count;
}

static int wrap(int m, int n)
{
    m %= n;
    return m < 0 ? m + n : m;
}

double bdl_tent_sample(const bdl_tent_field *f, const double x[3])
{
    double w[3][BDL_TENT_MAX];
    int first[3], count[3];
    for (int a = 0; a < 3; ++a)
        count[a] = axis_weights(f, a, x[a], &first[a], w[a]);
    double total = 0.0;
    for (int k = 0; k < count[2]; ++k) {
        const int iz = wrap(first[2] + k, f->n[2]);
        for (int j = 0; j < count[1]; ++j) {
            const int iy = wrap(first[1] + j, f->n[1]);
            const long row = ((long)iz * f->n[1] + iy) * f->n[0];
            for (int i = 0; i < count[0]; ++i)
                total += w[2][k] * w[1][j] * w[0][i] * f->cell[row + wrap(first[0] + i, f->n[0])];
        }
    }
    return total;
}
