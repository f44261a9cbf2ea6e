/*---------------------------------------------------------------------------*\
  demFoam DEM core - what the two spring-dashpot laws of Silbert et al.
  (Phys. Rev. E 2001, [S] eqs. 17-26) share: the kernel with a force scale,
  restitution, pair constants and the damped period (docs/theory.md,
  "Contact laws").  Included by laws/linearSpringDashpot.c and
  laws/hertzSpringDashpot.c only.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#ifndef DEM_SPRING_DASHPOT_H
#define DEM_SPRING_DASHPOT_H
#include "wallLoop.h"

static double sd_stiffness(const dem_material *m) { return m->stiffness_n; }

/* the restitution as given (the damping in N s/m needs the pair's mass) */
static void sd_derived(const dem_material *m, double *e, double *c)
{
    *e = m->restitution > 0 ? m->restitution : -1.0;
    *c = m->damping;
}

/* k_n, k_t in series (a rigid side: the other's alone); eta from e or as given */
static void sd_pair(dem_pair *q, const dem_material *a, double ea, double ca, const dem_material *b,
                    double eb, double cb, int like, int ra, int rb)
{
    if (ra != rb) {
        const dem_material *soft = ra ? b : a;
        q->kn = soft->stiffness_n;
        q->kt = soft->stiffness_t;
    } else {
        q->kn = like ? a->stiffness_n : a->stiffness_n * b->stiffness_n / (a->stiffness_n + b->stiffness_n);
        q->kt = like ? a->stiffness_t : a->stiffness_t * b->stiffness_t / (a->stiffness_t + b->stiffness_t);
    }
    if (ea > 0 && eb > 0) {
        q->e = fmin(ea, eb);
        q->beta = dem_lsd_beta(q->e);
        q->eta_fixed = -1.0;
    } else {
        q->e = -1.0;
        q->eta_fixed = fmax(ea > 0 ? -1.0 : ca, eb > 0 ? -1.0 : cb);
        q->beta = 0.0;
    }
}

/* half period of the damped linear oscillator */
static double sd_linear_time(const dem_time_pair *p)
{
    const dem_pair *q = p->q;
    double eta = q->eta_fixed >= 0 ? q->eta_fixed : q->beta * sqrt(q->kn * p->meff);
    double gam = eta / p->meff, om2 = q->kn / p->meff - 0.25 * gam * gam;
    return om2 > 0 ? DEM_PI / sqrt(om2) : INFINITY;
}

/* Spring-dashpot [S] 17-26; fscale = 1 (linear) or sqrt(delta/d) (Hertzian). */
static inline void sd_force(const dem_pair *q, double dt, const double n[3], double delta,
                            double fscale, const double vc[3], double meff, double *h,
                            double F[3], double ft[3], double *fel, double *fnout)
{
    double vn = vc[0] * n[0] + vc[1] * n[1] + vc[2] * n[2];
    double vt[3] = {vc[0] - vn * n[0], vc[1] - vn * n[1], vc[2] - vn * n[2]};
    double eta = q->eta_fixed >= 0.0 ? q->eta_fixed : q->beta * sqrt(q->kn * meff); /* gamma_n m_eff */
    double etat = 0.5 * eta;  /* tangential damping: half the normal one (LAMMPS gran/hooke/history default) */
    double fel_ = fscale * q->kn * delta;
    double fn = fel_ - fscale * eta * vn;
    if (q->pred > 0.0) fn = fel_ - fscale * eta * dem_predicted_vn(vn, fel_, fscale * eta, meff, 0.5 * dt);
    ft[0] = ft[1] = ft[2] = 0.0;
    if (q->mu > 0.0) {
        dem_rotate_history(h, n);
        h[0] += vt[0] * dt; h[1] += vt[1] * dt; h[2] += vt[2] * dt;
        for (int k = 0; k < 3; ++k) ft[k] = fscale * (-q->kt * h[k] - etat * vt[k]);
        double ftm = sqrt(ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2]);
        double lim = q->mu * fabs(fn);
        if (ftm > lim) {
            double s = lim / (ftm + (ftm > 0.0 ? 0.0 : 1.0));
            double fs = fscale + (fscale > 0.0 ? 0.0 : 1.0), on = fscale > 0.0 ? 1.0 : 0.0;
            for (int k = 0; k < 3; ++k) {
                ft[k] *= s;
                /* keep the spring consistent with the truncated force */
                h[k] = on * -(ft[k] / fs + etat * vt[k]) / q->kt;
            }
        }
    } else {
        h[0] = h[1] = h[2] = 0.0;
    }
    F[0] = fn * n[0] + ft[0]; F[1] = fn * n[1] + ft[1]; F[2] = fn * n[2] + ft[2];
    *fel = fel_;
    *fnout = fn;
}

#endif
