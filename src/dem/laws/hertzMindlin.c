/*---------------------------------------------------------------------------*\
  demFoam DEM core - contact law hertzMindlin: Hertz normal force and the
  Mindlin-Deresiewicz tangential force of Zhou et al. (Powder Technol. 1999,
  [Z] Table 2) with rolling friction; docs/theory.md, "Contact laws".
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "wallLoop.h"
#include <string.h>

double dem_hm_stiffness(const dem_material *m) { return m->youngs_modulus; }

/* e from c_n or c_n from e: the dimensionless impact of restitution.c */
void dem_hm_derived(const dem_material *m, double *e, double *c)
{
    if (m->restitution > 0) { *e = m->restitution; *c = dem_hm_damping(m->restitution); }
    else { *c = m->damping; *e = dem_hm_restitution(m->damping); }
}

/* a rigid side has 1/E = 0 in E* */
void dem_hm_pair_normal(dem_pair *q, const dem_material *a, double ea, double ca,
                        const dem_material *b, double eb, double cb)
{
    q->estar = 1.0 / ((1.0 - a->poisson_ratio * a->poisson_ratio) / a->youngs_modulus +
                      (1.0 - b->poisson_ratio * b->poisson_ratio) / b->youngs_modulus);
    q->e = fmin(ea, eb);
    q->cn = q->ct = (ea <= eb) ? ca : cb;
    q->k43 = 4.0 / 3.0 * q->estar;
    q->cn8 = q->cn * sqrt(8.0 * q->estar);
}

static void pair(dem_pair *q, const dem_material *a, double ea, double ca, const dem_material *b,
                 double eb, double cb, int like, int ra, int rb)
{
    (void)like; (void)ra; (void)rb;
    dem_hm_pair_normal(q, a, ea, ca, b, eb, cb);
    q->mumind = q->mu * q->mindlin;
    q->imumind = q->mumind > 0 ? 1.0 / q->mumind : 0.0;
    q->k43_mind = q->k43 / q->mindlin;
    q->ct8 = q->ct * sqrt(8.0 * q->estar / q->mindlin);
}

/* Rayleigh time pi R sqrt(rho/G) / (0.1631 nu + 0.8766) (Rayleigh-wave
 * speed fit; Li, Xu & Thornton, Powder Technol. 160 (2005) 219). */
static double rayleigh_time(double r, double rho, double E, double nu)
{
    double G = E / (2.0 * (1.0 + nu));
    return DEM_PI * r * sqrt(rho / G) / (0.1631 * nu + 0.8766);
}

static double contact_time(const dem_time_pair *p, double v_imp, int rayleigh, int damped)
{
    double t = INFINITY;
    if (v_imp > 0) t = dem_hertz_time(p->meff, p->rstar, p->q->estar, v_imp);
    if (v_imp > 0 && damped) t *= dem_hm_time_ratio(p->q->cn);  /* same scaled ODE, c_n only */
    if (rayleigh || !(v_imp > 0))
        t = fmin(t, rayleigh_time(p->rmin, p->rhomax, p->a->youngs_modulus, p->a->poisson_ratio));
    return t;
}

/* Hertz-Mindlin [Z] Table 2.  Returns the force on i in F, the elastic
 * normal force |f_cn| in *fel, tangential force in ft.  In terms of the
 * pair constants (no divisions by material data in the loop):
 *   f_cn  = (4/3) E* sqrt(R* delta) delta
 *   f_dn  = -c_n sqrt(8 E*) sqrt(m sqrt(R* delta)) v_n
 *   mu |f_cn| / delta_t,max = (4/3) E* sqrt(R* delta) / mindlin
 *   f_dt  = -c_t sqrt(8 E* / mindlin) sqrt(m sqrt(R* delta)) (1 - x)^(1/4) v_t,
 *           x = |delta_t| / delta_t,max                                   */
static inline void hm_force(const dem_pair *q, double dt, const double n[3], double delta, double d,
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
    if (q->mu > 0.0) {
        dem_rotate_history(h, n);
        h[0] += vt[0] * dt; h[1] += vt[1] * dt; h[2] += vt[2] * dt;
        double dtmax = q->mumind * delta;                           /* delta_t,max */
        double hm2 = h[0] * h[0] + h[1] * h[1] + h[2] * h[2];
        double kt = q->k43_mind * sq;                               /* mu |f_cn| / delta_t,max */
        if (!(dtmax > 0.0)) {                                       /* delta rounded to 0 */
            h[0] = h[1] = h[2] = 0.0;
        } else if (hm2 >= dtmax * dtmax) {                          /* Coulomb sliding */
            double s = dtmax / sqrt(hm2 + (hm2 > 0.0 ? 0.0 : 1.0));
            h[0] *= s; h[1] *= s; h[2] *= s;
            ft[0] = -kt * h[0]; ft[1] = -kt * h[1]; ft[2] = -kt * h[2];   /* -mu |f_cn| h/|h| */
        } else {
            double r = 1.0, c = 0.0;
            if (hm2 > 0.0) {
                double hm = sqrt(hm2), inv = 1.0 / ((hm + (hm > 0.0 ? 0.0 : 1.0)) * dtmax);
                double x = hm * hm * inv;                           /* |h| / delta_t,max */
                r = 1.0 - x;
                r = 0.5 * (r + fabs(r));
                double sr = sqrt(r);
                /* mu f_cn (1 - r^(3/2)) / |h| = kt (1 - r^(3/2)) / x */
                c = -kt * (1.0 - r * sr) * dtmax * dtmax * inv;
                ft[0] = c * h[0]; ft[1] = c * h[1]; ft[2] = c * h[2];
                r = sr;                                             /* (1 - x)^(1/2) */
            }
            double cd = -q->ct8 * dn * sqrt(r);                     /* (1 - x)^(1/4) */
            ft[0] += cd * vt[0]; ft[1] += cd * vt[1]; ft[2] += cd * vt[2];
        }
    } else {
        h[0] = h[1] = h[2] = 0.0;
    }
    F[0] = fn * n[0] + ft[0]; F[1] = fn * n[1] + ft[1]; F[2] = fn * n[2] + ft[2];
    *fel = fcn;
    *fnout = fn;
}

/* Hertz-Mindlin pair loop: the phased skeleton of contactKernel.h with the
 * [Z] law written branch-free.  With x = min(|h|/dtmax, 1),
 * r = 1 - x, sr = sqrt(r):
 *   sliding (x = 1): h is scaled to |h| = dtmax, f_t = -mu f_cn h/|h|;
 *   else             f_t = -mu f_cn (1 - r^(3/2)) h/|h| - c_t (...)(1-x)^(1/4) v_t.
 * Both are f_t = -kt g sc h - c_t sqrt(8 E* / mindlin) dn sqrt(sr) v_t with
 *   kt = mu f_cn / dtmax, g = (1 - r^(3/2))/x = (1 + sr + r)/(1 + sr),
 *   sc = min(1, dtmax/|h|),
 * since at x = 1: g = 1, sr = 0 (no damping while sliding, as in [Z]). */
typedef struct {
    double *dn, *fcn, *meff, *idt, *kt, *ct8, *cn8, *g, *sc, *q4, *crol, *mur;
    double *F0, *F1, *F2, *Ti0, *Ti1, *Ti2, *Tj0, *Tj1, *Tj2, *me;
    /* uniform (one material): the pair constants as loop invariants instead of per-contact copies */
    double u_cn8, u_ct8, u_k43, u_k43m, u_imm, u_mm, u_mur;
} hm_law;
#define HM_NDOUBLE 22
DEM_PHASED_FITS(HM_NDOUBLE);

/* the law's buffers and the constants of the one pair (uniform) */
static DEM_ALWAYS_INLINE void hm_init(const dem_world *w, void *vL, double *p, size_t cap)
{
    hm_law *b = vL;
    const dem_pair *q0 = w->pair;
    b->u_cn8 = q0->cn8; b->u_ct8 = q0->mu > 0.0 ? q0->ct8 : 0.0; b->u_k43 = q0->k43;
    b->u_k43m = q0->k43_mind; b->u_imm = q0->imumind; b->u_mm = q0->mumind; b->u_mur = q0->mu_r;
    double **f[HM_NDOUBLE] = {&b->dn, &b->fcn, &b->meff, &b->idt, &b->kt, &b->ct8, &b->cn8, &b->g, &b->sc,
                              &b->q4, &b->crol, &b->mur, &b->F0, &b->F1, &b->F2, &b->Ti0, &b->Ti1, &b->Ti2,
                              &b->Tj0, &b->Tj1, &b->Tj2, &b->me};
    dem_phased_assign(f, HM_NDOUBLE, p, cap);
}

/* phase 1, several materials: the pair's constants */
static DEM_ALWAYS_INLINE void hm_consts(const dem_phased_buf *B, void *vL, int a, const dem_pair *q)
{
    hm_law *L = vL;
    (void)B;
    L->cn8[a] = q->cn8; L->ct8[a] = q->mu > 0.0 ? q->ct8 : 0.0;
    L->kt[a] = q->k43; L->sc[a] = q->k43_mind; L->idt[a] = q->imumind; L->g[a] = q->mumind;
    L->mur[a] = q->mu_r;
}

/* phase 2 (vector): geometry, normal force */
static DEM_ALWAYS_INLINE void hm_geometry(const dem_world *w, const dem_phased_buf *B, void *vL, int nc,
                                          const int uniform, const int pred)
{
    const hm_law *L = vL;
    (void)w;
    double *restrict Bd0 = B->d0, *restrict Bd1 = B->d1, *restrict Bd2 = B->d2, *restrict Bdelta = B->delta;
    const double *restrict Bs = B->s, *restrict Bmi = B->mi, *restrict Bmj = B->mj, *restrict Bai = B->ai,
                 *restrict Baj = B->aj;
    double *restrict Bdn = L->dn, *restrict Bfcn = L->fcn, *restrict Bmeff = L->meff, *restrict Bidt = L->idt,
           *restrict Bkt = L->kt, *restrict Bsc = L->sc, *restrict Bg = L->g, *restrict Bme = L->me;
    DEM_IVDEP
    for (int a = 0; a < nc; ++a) {
        const double r0 = sqrt(Bd0[a] * Bd0[a] + Bd1[a] * Bd1[a] + Bd2[a] * Bd2[a]);
        const double s = Bs[a], msum = Bmi[a] + Bmj[a];
        const double r = r0 + (r0 > 0.0 ? 0.0 : s);  /* coincident centres: treated as delta = 0 */
        const double delta = s - r;            /* may round to 0 although r2 < s^2 */
        const double ds = delta + (delta > 0.0 ? 0.0 : s);  /* no select around the division */
        const double inv = 1.0 / (r * s * msum * ds);  /* 1/r, 1/s, 1/(mi+mj), 1/delta */
        const double ir = inv * s * msum * ds;
        Bd0[a] *= ir; Bd1[a] *= ir; Bd2[a] *= ir;
        const double meff = Bmi[a] * Bmj[a] * (inv * r * s * ds);
        const double rstar = Bai[a] * Baj[a] * (inv * r * msum * ds);
        const double sq = sqrt(rstar * delta);
        const double k43 = uniform ? L->u_k43 : Bkt[a];
        Bdelta[a] = delta;
        Bfcn[a] = k43 * sq * delta;
        Bdn[a] = sqrt(meff * sq);
        if (pred) Bme[a] = meff;
        Bmeff[a] = (uniform ? L->u_mm : Bg[a]) * delta;                 /* delta_t,max = mu mindlin delta */
        Bidt[a] = (uniform ? L->u_imm : Bidt[a]) * (inv * r * s * msum); /* 1/delta_t,max (mu = 0: 0) */
        Bkt[a] = (uniform ? L->u_k43m : Bsc[a]) * sq;                    /* mu f_cn / delta_t,max */
    }
}

/* phases 4 to 6: tangential law and rolling factors, forces and torques,
 * scatter (rec: phase 5 keeps f_n and f_t in the dead v_n, v_t buffers
 * for the contact record in phase 6) */
static DEM_ALWAYS_INLINE void hm_forces(dem_world *w, const dem_phased_buf *B, void *vL, int nc,
                                        const int uniform, const int pred, const int rec)
{
    const hm_law *L = vL;
    const double dt = w->hdt;
    const double dtl = w->cfg.dt;  /* step of the rolling-torque limiter */
    const double hp = 0.5 * dt;    /* pred: the last half step */
    double *f = w->f, *t = w->t, *nbh = w->nb_h;
    const double *restrict Bd0 = B->d0, *restrict Bd1 = B->d1, *restrict Bd2 = B->d2, *restrict Bai = B->ai,
                 *restrict Baj = B->aj, *restrict Bmj = B->mj, *restrict BIi = B->Ii, *restrict Bdelta = B->delta,
                 *restrict Bwr0 = B->wr0, *restrict Bwr1 = B->wr1, *restrict Bwr2 = B->wr2;
    double *restrict Bvn = B->vn, *restrict Bvt0 = B->vt0, *restrict Bvt1 = B->vt1, *restrict Bvt2 = B->vt2,
           *restrict Bh0 = B->h0, *restrict Bh1 = B->h1, *restrict Bh2 = B->h2;
    const int *restrict Bj = B->j, *restrict Bk = B->k, *restrict Bi = B->i;
    double *restrict Bdn = L->dn, *restrict Bfcn = L->fcn, *restrict Bmeff = L->meff, *restrict Bidt = L->idt,
           *restrict Bkt = L->kt, *restrict Bct8 = L->ct8, *restrict Bcn8 = L->cn8, *restrict Bg = L->g,
           *restrict Bsc = L->sc, *restrict Bq4 = L->q4, *restrict Bcrol = L->crol, *restrict Bmur = L->mur,
           *restrict BF0 = L->F0, *restrict BF1 = L->F1, *restrict BF2 = L->F2,
           *restrict BTi0 = L->Ti0, *restrict BTi1 = L->Ti1, *restrict BTi2 = L->Ti2,
           *restrict BTj0 = L->Tj0, *restrict BTj1 = L->Tj1, *restrict BTj2 = L->Tj2, *restrict Bme = L->me;
    const int roll = uniform != 2;  /* 0: mu_r = 0, no rolling torque (DEM_PHASED_DISPATCH) */
    /* phase 4 (vector): tangential law factors, rolling factor */
    DEM_IVDEP
    for (int a = 0; a < nc; ++a) {
        /* history: rotated, h += v_t dt */
        double hs[3] = {Bh0[a], Bh1[a], Bh2[a]};
        dem_history_step(Bd0[a], Bd1[a], Bd2[a], Bvt0[a], Bvt1[a], Bvt2[a], dt, hs);
        double h0 = hs[0], h1 = hs[1], h2 = hs[2];
        const int fric = Bidt[a] > 0.0;        /* mu = 0: no tangential spring */
        h0 = fric ? h0 : 0.0; h1 = fric ? h1 : 0.0; h2 = fric ? h2 : 0.0;
        Bh0[a] = h0; Bh1[a] = h1; Bh2[a] = h2;
        /* clamps and guards are arithmetic (no select feeding sqrt or a
           division), so no floating-point exception can be raised even
           where the compiler evaluates both sides of a select */
        const double hm = sqrt(h0 * h0 + h1 * h1 + h2 * h2);
        const double r1 = 1.0 - hm * Bidt[a];
        const double r = 0.5 * (r1 + fabs(r1));              /* max(1 - x, 0) */
        const double sr = sqrt(r);
        const double hmsafe = hm + (hm > 0.0 ? 0.0 : 1.0);
        const double inv = 1.0 / (hmsafe * (1.0 + sr));
        const double dtmax_over_hm = Bmeff[a] * (1.0 + sr) * inv;  /* dtmax / |h| */
        Bsc[a] = dtmax_over_hm < 1.0 ? dtmax_over_hm : 1.0;
        Bg[a] = (1.0 + sr + r) * hmsafe * inv;
        Bq4[a] = sqrt(sr);
        /* rolling: c = -min(mu_r f_cn / wm, Ii Ij / (dt (Ii + Ij))) */
        if (!roll) continue;
        const double wm = sqrt(Bwr0[a] * Bwr0[a] + Bwr1[a] * Bwr1[a] + Bwr2[a] * Bwr2[a]);
        const double wmsafe = wm + (wm > 0.0 ? 0.0 : 1.0);
        const double Ii = BIi[a], Ij = 0.4 * Bmj[a] * Baj[a] * Baj[a], den = dtl * (Ii + Ij);
        const double inv2 = 1.0 / (wmsafe * den);
        const double c1 = (uniform ? L->u_mur : Bmur[a]) * Bfcn[a] * den * inv2, c2 = Ii * Ij * wmsafe * inv2;
        Bcrol[a] = wm > 0.0 ? -(c1 < c2 ? c1 : c2) : 0.0;
    }
    /* phase 5 (vector): history limit, forces and torques */
    DEM_IVDEP
    for (int a = 0; a < nc; ++a) {
        const double aj = Baj[a], ai = Bai[a];
        const double n0 = Bd0[a], n1 = Bd1[a], n2 = Bd2[a];
        const double sc = Bsc[a];
        const double h0 = sc < 1.0 ? Bh0[a] * sc : Bh0[a], h1 = sc < 1.0 ? Bh1[a] * sc : Bh1[a],
                     h2 = sc < 1.0 ? Bh2[a] * sc : Bh2[a];
        Bh0[a] = h0; Bh1[a] = h1; Bh2[a] = h2;
        const double ce = -Bkt[a] * Bg[a], cd = -(uniform ? L->u_ct8 : Bct8[a]) * Bdn[a] * Bq4[a];
        const double ft0 = ce * h0 + cd * Bvt0[a];
        const double ft1 = ce * h1 + cd * Bvt1[a];
        const double ft2 = ce * h2 + cd * Bvt2[a];
        double fn = Bfcn[a] - (uniform ? L->u_cn8 : Bcn8[a]) * Bdn[a] * Bvn[a];
        if (pred) {   /* damping at the predicted end-of-step velocity (dem_predicted_vn) */
            const double C = (uniform ? L->u_cn8 : Bcn8[a]) * Bdn[a];
            fn = Bfcn[a] - C * ((Bme[a] * Bvn[a] + hp * Bfcn[a]) / (Bme[a] + hp * C));
        }
        BF0[a] = fn * n0 + ft0; BF1[a] = fn * n1 + ft1; BF2[a] = fn * n2 + ft2;
        if (rec) { Bvn[a] = fn; Bvt0[a] = ft0; Bvt1[a] = ft1; Bvt2[a] = ft2; }
        const double c0 = n1 * ft2 - n2 * ft1, c1 = n2 * ft0 - n0 * ft2, c2 = n0 * ft1 - n1 * ft0;
        if (roll) {
            const double cr = Bcrol[a];
            const double M0 = cr * Bwr0[a], M1 = cr * Bwr1[a], M2 = cr * Bwr2[a];
            BTi0[a] = M0 - ai * c0; BTi1[a] = M1 - ai * c1; BTi2[a] = M2 - ai * c2;
            BTj0[a] = aj * c0 + M0; BTj1[a] = aj * c1 + M1; BTj2[a] = aj * c2 + M2;
        } else {
            BTi0[a] = -(ai * c0); BTi1[a] = -(ai * c1); BTi2[a] = -(ai * c2);
            BTj0[a] = aj * c0; BTj1[a] = aj * c1; BTj2[a] = aj * c2;
        }
    }
    /* phase 6 (scatter): history, forces and torques */
    for (int a = 0; a < nc; ++a) {
        const int j = Bj[a], ii = Bi[a];
        double *h = nbh + 3 * (size_t)Bk[a];
        h[0] = Bh0[a]; h[1] = Bh1[a]; h[2] = Bh2[a];
        const double F0 = BF0[a], F1 = BF1[a], F2 = BF2[a];
        f[3 * ii] += F0; f[3 * ii + 1] += F1; f[3 * ii + 2] += F2;
        f[3 * j] -= F0; f[3 * j + 1] -= F1; f[3 * j + 2] -= F2;
        t[3 * ii] += BTi0[a]; t[3 * ii + 1] += BTi1[a]; t[3 * ii + 2] += BTi2[a];
        t[3 * j] -= BTj0[a]; t[3 * j + 1] -= BTj1[a]; t[3 * j + 2] -= BTj2[a];
        if (rec) {
            const double n[3] = {Bd0[a], Bd1[a], Bd2[a]}, ft[3] = {Bvt0[a], Bvt1[a], Bvt2[a]};
            dem_record_contact(w, (size_t)ii, j, 0, (size_t)ii >= w->n || (size_t)j >= w->n, Bdelta[a], n,
                               Bvn[a], ft);
        }
    }
}

/* always inlined: each call site is specialised for periodic/uniform/pred/rec */
static DEM_ALWAYS_INLINE void pair_loop_hm(dem_world *w, const int periodic, const int uniform, const int pred,
                                           const int rec, double *maxov, size_t *ncont)
{
    hm_law L;
    dem_phased_loop(w, &L, HM_NDOUBLE, hm_init, hm_consts, hm_geometry, hm_forces, periodic, uniform, pred, rec,
                    maxov, ncont);
}

/* The Hertz-Mindlin pair loops, compiled more than once where the compiler
 * supports function multiversioning: a generic x86-64 (SSE2) version and
 * versions for AVX2 and AVX-512 (wider vectors, more registers), chosen once
 * at load time from the CPU (ifunc).  All do the same IEEE operations in the
 * same order (no FMA: -std=c11 keeps -ffp-contract=off), so the results are
 * bit-identical on any x86-64; -DDEM_NO_MULTIVERSION builds the generic one only
 * (DEM_MULTIVERSION, dem_private.h). */
DEM_MULTIVERSION __attribute__((noinline))
static void pair_loops_hm(dem_world *w, int per, double *movr, size_t *nct)
{
    DEM_PHASED_DISPATCH(pair_loop_hm, w, per, movr, nct);
}

static void contact(const dem_pair *q, double dt, const double n[3], double delta, double d,
                    const double vc[3], double meff, double rstar, double *h,
                    double F[3], double ft[3], double *fel, double *fnout)
{
    hm_force(q, dt, n, delta, d, vc, meff, rstar, h, F, ft, fel, fnout);
}

/* hm_force over a block of wall contacts, branch-free: each of its cases
 * (no friction; delta_t,max rounded to 0; Coulomb sliding; sticking, with
 * |h| = 0 apart) computed with the same IEEE operations and selected, so the
 * results are hm_force's bit for bit.  Two loops: the guards of the
 * divisions (|h| and delta_t,max where they are 0) go through memory to the
 * second, because within one loop GCC (-fno-trapping-math) may undo a guard
 * and divide by zero in a lane whose result is not used, which OpenFOAM's
 * FOAM_SIGFPE traps (tests/dem/test_fpe.c). */
static DEM_ALWAYS_INLINE void hm_wall_block(const dem_world *w, dem_wall_block *b, int nc)
{
    const double dt = w->hdt, hp = 0.5 * dt;
    double k43[DEM_WALL_BLOCK], cn8[DEM_WALL_BLOCK], mumind[DEM_WALL_BLOCK], k43m[DEM_WALL_BLOCK],
        ct8[DEM_WALL_BLOCK], fric[DEM_WALL_BLOCK], pred[DEM_WALL_BLOCK];
    double dnA[DEM_WALL_BLOCK], dtmaxA[DEM_WALL_BLOCK], hmA[DEM_WALL_BLOCK], hmsA[DEM_WALL_BLOCK],
        dsafeA[DEM_WALL_BLOCK], ktA[DEM_WALL_BLOCK];
    for (int a = 0; a < nc; ++a) {
        const dem_pair *q = b->q[a];
        k43[a] = q->k43; cn8[a] = q->cn8; mumind[a] = q->mumind; k43m[a] = q->k43_mind; ct8[a] = q->ct8;
        fric[a] = q->mu > 0.0 ? 1.0 : 0.0; pred[a] = q->pred;
    }
    /* normal force, v_t (into vc), history advanced (into h), |h|, guards */
    DEM_IVDEP
    for (int a = 0; a < nc; ++a) {
        double sq, dn;
        dem_hertz_block_start(b, a, k43[a], cn8[a], pred[a], dt, hp, &sq, &dn);
        const double dtmax = mumind[a] * b->delta[a];
        const double hm = sqrt(b->h0[a] * b->h0[a] + b->h1[a] * b->h1[a] + b->h2[a] * b->h2[a]);
        dnA[a] = dn; dtmaxA[a] = dtmax; hmA[a] = hm; ktA[a] = k43m[a] * sq;
        /* hm_force's sqrt(hm2 + guard) is hm where it is used (hm2 > 0) */
        hmsA[a] = hm + (hm > 0.0 ? 0.0 : 1.0);
        dsafeA[a] = dtmax + (dtmax > 0.0 ? 0.0 : 1.0);
    }
    /* the tangential force of each case, selected */
    DEM_IVDEP
    for (int a = 0; a < nc; ++a) {
        const double h0 = b->h0[a], h1 = b->h1[a], h2 = b->h2[a];
        const double vt0 = b->vc0[a], vt1 = b->vc1[a], vt2 = b->vc2[a];
        const double dtmax = dtmaxA[a], kt = ktA[a], hm = hmA[a], hms = hmsA[a];
        const double hm2 = h0 * h0 + h1 * h1 + h2 * h2;
        const int zero = !(dtmax > 0.0) || !(fric[a] > 0.0);  /* no spring: h = 0, f_t = 0 */
        const int slide = hm2 >= dtmax * dtmax;
        /* sliding: h scaled back to |h| = delta_t,max, f_t = -kt h */
        const double s = dtmax / hms;
        const double hs0 = h0 * s, hs1 = h1 * s, hs2 = h2 * s;
        /* sticking: f_t = c h (|h| > 0) - c_t (...) sqrt(r) v_t */
        const double inv = 1.0 / (hms * dsafeA[a]);
        const double x = hm * hm * inv;
        const double r1 = 1.0 - x;
        const double r = 0.5 * (r1 + fabs(r1));
        const double sr = sqrt(r);
        const double c = -kt * (1.0 - r * sr) * dtmax * dtmax * inv;
        const int moved = hm2 > 0.0;
        const double cd = -ct8[a] * dnA[a] * sqrt(moved ? sr : 1.0);
        const double st0 = (moved ? c * h0 : 0.0) + cd * vt0, st1 = (moved ? c * h1 : 0.0) + cd * vt1,
                     st2 = (moved ? c * h2 : 0.0) + cd * vt2;
        const double ft0 = zero ? 0.0 : slide ? -kt * hs0 : st0;
        const double ft1 = zero ? 0.0 : slide ? -kt * hs1 : st1;
        const double ft2 = zero ? 0.0 : slide ? -kt * hs2 : st2;
        b->h0[a] = zero ? 0.0 : slide ? hs0 : h0;
        b->h1[a] = zero ? 0.0 : slide ? hs1 : h1;
        b->h2[a] = zero ? 0.0 : slide ? hs2 : h2;
        b->ft0[a] = ft0; b->ft1[a] = ft1; b->ft2[a] = ft2;
    }
}

DEM_WALL_FORCES_BLOCKED(wall_forces, contact, hm_wall_block)

const dem_law dem_law_hertzMindlin = {
    .name = "hertzMindlin",
    .stiffness_name = "youngs_modulus",
    .stiffness = dem_hm_stiffness,
    .derived = dem_hm_derived,
    .pair = pair,
    .contact_time = contact_time,
    .pair_forces = pair_loops_hm,
    .wall_forces = wall_forces,
};
