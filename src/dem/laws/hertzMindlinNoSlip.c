/*---------------------------------------------------------------------------*\
  demFoam DEM core - contact law hertzMindlinNoSlip: the Hertz normal force
  and damping of hertzMindlin ([Z] Table 2), with the incremental Mindlin
  no-slip tangential spring k_t = 8 G* sqrt(R* delta) (Mindlin, J. Appl.
  Mech. 1949) and a Coulomb limit mu f_cn, the spring rescaled to the limit
  while sliding; rolling friction as hertzMindlin.  docs/theory.md
  section 7.2.1.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "contactKernel.h"

/* shear modulus G = E / (2 (1 + nu)); a rigid side (E = inf) adds nothing */
static double shear_part(const dem_material *m)
{
    return isinf(m->youngs_modulus) ? 0.0
         : (2.0 - m->poisson_ratio) * 2.0 * (1.0 + m->poisson_ratio) / m->youngs_modulus;
}

static void pair(dem_pair *q, const dem_material *a, double ea, double ca, const dem_material *b,
                 double eb, double cb, int like, int ra, int rb)
{
    (void)like; (void)ra; (void)rb;
    dem_hm_pair_normal(q, a, ea, ca, b, eb, cb);  /* the normal part of hertzMindlin */
    q->g8 = 8.0 / (shear_part(a) + shear_part(b));
}

static double contact_time(const dem_time_pair *p, double v_imp, int rayleigh, int damped)
{
    return dem_law_hertzMindlin.contact_time(p, v_imp, rayleigh, damped);
}

/* f_n as hertzMindlin; tangential: the spring xi (history h, rotated into
 * the tangent plane, += v_t dt), f_t = -k_t xi - c_n sqrt(m* k_t) v_t
 * (tangential damping with the normal c_n), |f_t| <= mu f_cn; beyond the
 * limit f_t is scaled to it and xi set so that spring and damping give that
 * force, xi = -(f_t + c_t v_t)/k_t (as the spring-dashpot laws, 7.3). */
static inline void contact(const dem_pair *q, double dt, const double n[3], double delta, double d,
                           const double vc[3], double meff, double rstar, double *h,
                           double F[3], double ft[3], double *fel, double *fnout)
{
    (void)d;
    double vn = vc[0] * n[0] + vc[1] * n[1] + vc[2] * n[2];
    double vt[3] = {vc[0] - vn * n[0], vc[1] - vn * n[1], vc[2] - vn * n[2]};
    double sq = sqrt(rstar * delta);
    double fcn = q->k43 * sq * delta;
    double dn = sqrt(meff * sq);
    double fn = fcn - q->cn8 * dn * vn;
    if (q->pred > 0.0) fn = fcn - q->cn8 * dn * dem_predicted_vn(vn, fcn, q->cn8 * dn, meff, 0.5 * dt);
    ft[0] = ft[1] = ft[2] = 0.0;
    if (q->mu > 0.0 && delta > 0.0) {
        dem_rotate_history(h, n);
        h[0] += vt[0] * dt; h[1] += vt[1] * dt; h[2] += vt[2] * dt;
        const double kt = q->g8 * sq, ct = q->cn * sqrt(meff * kt);
        for (int k = 0; k < 3; ++k) ft[k] = -kt * h[k] - ct * vt[k];
        const double ftm = sqrt(ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2]), lim = q->mu * fcn;
        if (ftm > lim) {   /* Coulomb: force to the limit, spring + damping to that force */
            const double s = lim / ftm;
            for (int k = 0; k < 3; ++k) {
                ft[k] *= s;
                h[k] = -(ft[k] + ct * vt[k]) / kt;
            }
        }
    } else {
        h[0] = h[1] = h[2] = 0.0;
    }
    F[0] = fn * n[0] + ft[0]; F[1] = fn * n[1] + ft[1]; F[2] = fn * n[2] + ft[2];
    *fel = fcn;
    *fnout = fn;
}

static void pair_forces(dem_world *w, int periodic, double *max_overlap, size_t *contacts)
{
    dem_pair_loops(w, contact, periodic, max_overlap, contacts);
}

const dem_law dem_law_hertzMindlinNoSlip = {
    .name = "hertzMindlinNoSlip",
    .stiffness_name = "youngs_modulus",
    .stiffness = dem_hm_stiffness,
    .derived = dem_hm_derived,
    .pair = pair,
    .contact_time = contact_time,
    .pair_forces = pair_forces,
    .contact = contact,
};
