/* tiptap (internal): a root of a function inside a bracket, by the Illinois variant of
 * regula falsi. The solver's contact events and the grazing map's touch share it.
 *
 * Each step takes the secant's zero of the bracket (the midpoint should rounding put it
 * outside) and keeps the end whose value has the other sign; an end kept twice in a row
 * has its value halved, so that the bracket closes from both sides and convergence stays
 * superlinear (Dowell and Jarratt, BIT 12 (1972) 503).
 */
#ifndef TT_UTIL_ROOT_H
#define TT_UTIL_ROOT_H

#include <math.h>

/* The function whose root is sought, at x, with the caller's data. */
typedef double (*tt_root_fn)(double x, void *data);

/* A bracket: f(a) and f(b) of opposite signs (or one of them zero), a < b. */
typedef struct {
    double a, b;
    double fa, fb;
} tt_root_bracket;

/* Narrow br by at most maxit steps while b - a > xtol. Returns 1 with *x the step's point
 * where |f| <= ftol (ftol 0: an exact zero), else 0 with br the final bracket: the caller
 * chooses its point in it (the end on b's side to switch just past a root, say).
 * Inline, so that the function and its data are known where it runs: the events call
 * it at every contact switch. */
static inline int tt_root_illinois(tt_root_fn f, void *data, tt_root_bracket *br, double xtol,
                                   double ftol, int maxit, double *x)
{
    double a = br->a, b = br->b, fa = br->fa, fb = br->fb;
    int side = 0, found = 0;
    for (int it = 0; it < maxit && b - a > xtol; it++) {
        double m = (a * fb - b * fa) / (fb - fa);
        if (!(m > a && m < b))
            m = 0.5 * (a + b);
        double fm = f(m, data);
        if (fabs(fm) <= ftol) {
            *x = m;
            found = 1;
            break;
        }
        if ((fm > 0) == (fb > 0)) {
            b = m;
            fb = fm;
            if (side == 1)
                fa *= 0.5;
            side = 1;
        } else {
            a = m;
            fa = fm;
            if (side == -1)
                fb *= 0.5;
            side = -1;
        }
    }
    br->a = a, br->b = b, br->fa = fa, br->fb = fb;
    return found;
}


#endif
