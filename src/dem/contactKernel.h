/*---------------------------------------------------------------------------*\
  demFoam DEM core - pieces shared by the contact laws (laws/) and the
  wall loop (contact.c): history rotation, rolling friction, the scalar pair
  loop.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

  velocity of i relative to j is
      v_c = v_i - v_j - (a_i w_i + a_j w_j) x n,
  v_n = (v_c . n), v_t = v_c - v_n n, and every force below acts on i
  (j gets the opposite).  For a wall, j is the wall: n points from the
  contact point to the centre, a_j = infinity, m_eff = m_i, R* = a_i.
  This is the convention of [S] eqs. 17-26; [Z] Table 2 uses n from i to j
  with forces on i, which flips the signs of n, v_n and delta_t together.

  Laws (chosen once per call, never inside the pair loop):
  - Hertz-Mindlin [Z] Table 2 (hm_force), rolling friction
    M_r = -mu_r |f_cn| w_rel/|w_rel| limited so that it cannot reverse w_rel
    within one step (a numerical regularisation; see docs/demCore.md).
\*---------------------------------------------------------------------------*/
#ifndef DEM_CONTACT_KERNEL_H
#define DEM_CONTACT_KERNEL_H
#include "law.h"
#include <math.h>

#if defined(__GNUC__)
#define DEM_ALWAYS_INLINE __attribute__((always_inline)) inline
#else
#define DEM_ALWAYS_INLINE inline
#endif

static inline void dem_rotate_history(double *h, const double n[3])
{
    double hn = h[0] * n[0] + h[1] * n[1] + h[2] * n[2];
    if (hn != 0.0) {
        double h2 = h[0] * h[0] + h[1] * h[1] + h[2] * h[2];
        h[0] -= hn * n[0]; h[1] -= hn * n[1]; h[2] -= hn * n[2];
        double h2n = h[0] * h[0] + h[1] * h[1] + h[2] * h[2];
        /* rescale to the old length; skipped when the projection shortened
           it by less than 5e-13 relative (quasi-static contacts: the normal
           turns by ~1e-7 per step; the loss then stays below ~1e-6 over 1e6
           steps of one contact) */
        if (h2n > 0.0 && hn * hn > 1e-12 * h2n) {
            double s = sqrt(h2 / (h2n + (h2n > 0.0 ? 0.0 : 1.0)));
            h[0] *= s; h[1] *= s; h[2] *= s;
        }
    }
}

/* Rolling friction torque on i (j gets the opposite): -mu_r |f_cn| w/|w|,
 * w = w_i - w_j, magnitude limited to |w| / (dt (1/I_i + 1/I_j)) so that it
 * cannot reverse w within a step.  Ii, Ij: moments of inertia (Ij = 0: wall). */
/* The relative normal velocity at the end of the step, predicted from the
 * half-step one v (velocity Verlet) with the pair's own force over the last
 * half step h: v* = v + h (f_el - C v*) / m*, solved for v* (C: the normal
 * damping coefficient of the contact; docs/theory.md, "Damping in the time step"). */
static inline double dem_predicted_vn(double vn, double fel, double C, double meff, double h)
{
    return (meff * vn + h * fel) / (meff + h * C);
}

static inline void dem_rolling(double mu_r, double fel, const double *wi, const double *wj,
                               double Ii, double Ij, double dt, double M[3])
{
    double wr[3] = {wi[0] - (wj ? wj[0] : 0), wi[1] - (wj ? wj[1] : 0), wi[2] - (wj ? wj[2] : 0)};
    double wm2 = wr[0] * wr[0] + wr[1] * wr[1] + wr[2] * wr[2];
    if (wm2 <= 0.0) { M[0] = M[1] = M[2] = 0.0; return; }
    double wm = sqrt(wm2), m = mu_r * fel, c;
    /* limit m <= wm Ii Ij / (dt (Ii + Ij)); wall (Ij -> inf): wm Ii / dt */
    double num = Ij > 0 ? Ii * Ij : Ii, den = Ij > 0 ? dt * (Ii + Ij) : dt;
    double inv = 1.0 / ((wm + (wm > 0.0 ? 0.0 : 1.0)) * (den + (den > 0.0 ? 0.0 : 1.0)));
    if (m * den > wm * num) c = -num * wm * inv;
    else c = -m * den * inv;
    M[0] = c * wr[0]; M[1] = c * wr[1]; M[2] = c * wr[2];
}

/* Append one contact to the record (capacity ensured by dem_forces). */
static inline void dem_record_contact(dem_world *w, size_t a, int64_t b, int wall, int ghost, double delta,
                                      const double n[3], double fn, const double ft[3])
{
    dem_contact *c = w->crec + w->ncrec++;
    c->id_a = w->id[a]; c->id_b = wall ? b : w->id[b];
    c->wall = wall; c->ghost = ghost; c->overlap = delta;
    for (int k = 0; k < 3; ++k) {
        c->normal[k] = n[k];
        c->force_n[k] = fn * n[k];   /* the product the kernel adds to ft (law.h) */
        c->force_t[k] = ft[k];
    }
}

/* The scalar pair loop of a law whose kernel is `one` (a constant at each
 * call site, so that the compiler inlines it), specialised by periodicity
 * and by recording (record = 1: each touching pair also goes to w->crec). */
static DEM_ALWAYS_INLINE void dem_pair_loop(dem_world *w, dem_contact_fn one, const int periodic,
                                            const int record, double *maxov, size_t *ncont)
{
    const double dt = w->hdt;
    const int nm = w->nmat;
    const dem_pair *pt = w->pair;
    const double *x = w->x, *v = w->v, *om = w->w, *rad = w->rad, *mass = w->mass;
    const int *mat = w->mat_of;
    double *f = w->f, *t = w->t;
    const int *off = w->nb_off, *nbj = w->nb_j;
    const unsigned char *nbs = w->nb_s;
    double *nbh = w->nb_h;
    double movr = *maxov;
    size_t nct = 0;
    const size_t nrows = w->nrows;
    for (size_t i = 0; i < nrows; ++i) {
        const int k0 = off[i], k1 = off[i + 1];
        if (k0 == k1) continue;
        const double xi0 = x[3 * i], xi1 = x[3 * i + 1], xi2 = x[3 * i + 2];
        const double ai = rad[i], mi = mass[i];
        const double *wi = om + 3 * i, *vi = v + 3 * i;
        const dem_pair *prow = pt + (size_t)mat[i] * nm;
        double fi0 = 0, fi1 = 0, fi2 = 0, ti0 = 0, ti1 = 0, ti2 = 0;
        for (int k = k0; k < k1; ++k) {
            const size_t j = (size_t)nbj[k];
            double d0 = xi0 - x[3 * j], d1 = xi1 - x[3 * j + 1], d2 = xi2 - x[3 * j + 2];
            if (periodic) {
                const double *sh = w->shift[nbs[k]];
                d0 += sh[0]; d1 += sh[1]; d2 += sh[2];
            }
            const double aj = rad[j], s = ai + aj;
            const double r2 = d0 * d0 + d1 * d1 + d2 * d2;
            double *h = nbh + 3 * (size_t)k;
            if (r2 >= s * s) {
                if (h[0] != 0.0 || h[1] != 0.0 || h[2] != 0.0) h[0] = h[1] = h[2] = 0.0;
                continue;
            }
            const double r = sqrt(r2), mj = mass[j], msum = mi + mj;
            const double inv = 1.0 / ((r + (r > 0.0 ? 0.0 : 1.0)) * s * msum);  /* one division for 1/r, 1/s, 1/(mi+mj) */
            const double ir = inv * s * msum;
            const double n[3] = {d0 * ir, d1 * ir, d2 * ir};
            const double delta = s - r;
            nct++;
            if (delta > movr * s) movr = delta / s;
            const double meff = mi * mj * (inv * r * s);
            const double rstar = ai * aj * (inv * r * msum);
            const double *wj = om + 3 * j, *vj = v + 3 * j;
            /* (a_i w_i + a_j w_j) x n */
            const double W0 = ai * wi[0] + aj * wj[0], W1 = ai * wi[1] + aj * wj[1],
                         W2 = ai * wi[2] + aj * wj[2];
            const double vc[3] = {vi[0] - vj[0] - (W1 * n[2] - W2 * n[1]),
                                  vi[1] - vj[1] - (W2 * n[0] - W0 * n[2]),
                                  vi[2] - vj[2] - (W0 * n[1] - W1 * n[0])};
            const dem_pair *q = prow + mat[j];
            double F[3], ft[3], fel, fn;
            one(q, dt, n, delta, s, vc, meff, rstar, h, F, ft, &fel, &fn);
            if (record) dem_record_contact(w, i, (int64_t)j, 0, i >= w->n || j >= w->n, delta, n, fn, ft);
            fi0 += F[0]; fi1 += F[1]; fi2 += F[2];
            f[3 * j] -= F[0]; f[3 * j + 1] -= F[1]; f[3 * j + 2] -= F[2];
            /* torques: T_i = -a_i n x f_t, T_j = -a_j n x f_t */
            const double c0 = n[1] * ft[2] - n[2] * ft[1], c1 = n[2] * ft[0] - n[0] * ft[2],
                         c2 = n[0] * ft[1] - n[1] * ft[0];
            ti0 -= ai * c0; ti1 -= ai * c1; ti2 -= ai * c2;
            t[3 * j] -= aj * c0; t[3 * j + 1] -= aj * c1; t[3 * j + 2] -= aj * c2;
            if (q->mu_r > 0.0) {
                double M[3];
                dem_rolling(q->mu_r, fel, wi, wj, 0.4 * mi * ai * ai, 0.4 * mj * aj * aj, w->cfg.dt, M);
                ti0 += M[0]; ti1 += M[1]; ti2 += M[2];
                t[3 * j] -= M[0]; t[3 * j + 1] -= M[1]; t[3 * j + 2] -= M[2];
            }
        }
        f[3 * i] += fi0; f[3 * i + 1] += fi1; f[3 * i + 2] += fi2;
        t[3 * i] += ti0; t[3 * i + 1] += ti1; t[3 * i + 2] += ti2;
    }
    *maxov = movr;
    *ncont = nct;
}

/* A law's pair_forces with the scalar loop: the specialisation by
 * periodicity and recording chosen once per force evaluation. */
static DEM_ALWAYS_INLINE void dem_pair_loops(dem_world *w, dem_contact_fn one, int periodic,
                                             double *maxov, size_t *ncont)
{
    if (w->crec_now) {  /* the recording loop (same arithmetic) */
        if (periodic) dem_pair_loop(w, one, 1, 1, maxov, ncont);
        else dem_pair_loop(w, one, 0, 1, maxov, ncont);
    } else if (periodic) dem_pair_loop(w, one, 1, 0, maxov, ncont);
    else dem_pair_loop(w, one, 0, 0, maxov, ncont);
}

#endif
