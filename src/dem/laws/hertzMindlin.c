/*---------------------------------------------------------------------------*\
  demFoam DEM core - contact law hertzMindlin: Hertz normal force and the
  Mindlin-Deresiewicz tangential force of Zhou et al. (Powder Technol. 1999,
  [Z] Table 2) with rolling friction; docs/theory.md, "Contact laws".
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "contactKernel.h"
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

/* contacts processed per block in the phased Hertz-Mindlin loop */
#define DEM_HM_BLOCK 64
_Static_assert(DEM_SCRATCH_EXTRA >= DEM_HM_BLOCK, "scratch must hold a block plus the longest row");

/* independent iterations (distinct SoA buffers): let GCC vectorise */
#if defined(__GNUC__) && !defined(__clang__)
#define DEM_IVDEP _Pragma("GCC ivdep")
#else
#define DEM_IVDEP
#endif

/* Hertz-Mindlin pair loop, phased per row.  The contacts of row i are
 * collected into structure-of-arrays buffers, then each phase runs over all
 * of them: gathers (positions, velocities, history) stay scalar, while the
 * arithmetic with square roots and divisions runs in branch-free loops the
 * compiler vectorises, so these long-latency operations overlap instead of
 * forming one dependent chain per contact.
 *
 * The [Z] tangential law is written branch-free.  With x = min(|h|/dtmax, 1),
 * r = 1 - x, sr = sqrt(r):
 *   sliding (x = 1): h is scaled to |h| = dtmax, f_t = -mu f_cn h/|h|;
 *   else             f_t = -mu f_cn (1 - r^(3/2)) h/|h| - c_t (...)(1-x)^(1/4) v_t.
 * Both are f_t = -kt g sc h - c_t sqrt(8 E* / mindlin) dn sqrt(sr) v_t with
 *   kt = mu f_cn / dtmax, g = (1 - r^(3/2))/x = (1 + sr + r)/(1 + sr),
 *   sc = min(1, dtmax/|h|),
 * since at x = 1: g = 1, sr = 0 (no damping while sliding, as in [Z]). */
typedef struct {
    int *j, *k;
    double *d0, *d1, *d2, *s, *mj, *aj;
    double *delta, *dn, *fcn, *meff, *idt;
    double *vn, *vt0, *vt1, *vt2, *kt, *ct8, *cn8;
    double *g, *sc, *q4;
    double *wm2, *crol, *mur, *ai, *mi, *Ii, *wr0, *wr1, *wr2, *h0, *h1, *h2;
    double *F0, *F1, *F2, *Ti0, *Ti1, *Ti2, *Tj0, *Tj1, *Tj2;
    double *me;
    const dem_pair **q;
    int *i;
} hm_soa;

static void soa_map(hm_soa *b, void *mem, size_t cap)
{
    double *p = (double *)mem;
    double **f[] = {&b->d0, &b->d1, &b->d2, &b->s, &b->mj, &b->aj,
                    &b->delta, &b->dn, &b->fcn, &b->meff, &b->idt,
                    &b->vn, &b->vt0, &b->vt1, &b->vt2, &b->kt, &b->ct8, &b->cn8,
                    &b->g, &b->sc, &b->q4, &b->wm2, &b->crol, &b->mur,
                    &b->ai, &b->mi, &b->Ii, &b->wr0, &b->wr1, &b->wr2,
                    &b->h0, &b->h1, &b->h2, &b->F0, &b->F1, &b->F2,
                    &b->Ti0, &b->Ti1, &b->Ti2, &b->Tj0, &b->Tj1, &b->Tj2, &b->me};
    size_t nf = sizeof f / sizeof f[0];
    for (size_t a = 0; a < nf; ++a) { *f[a] = p; p += cap; }
    b->q = (const dem_pair **)p; p += cap;
    b->j = (int *)p;
    b->k = b->j + cap;
    b->i = b->k + cap;
}
_Static_assert(44 * sizeof(double) + 3 * sizeof(int) <= DEM_SCRATCH_ENTRY, "scratch entry too small for the SoA buffers");

/* always inlined: each call site is specialised for periodic/uniform/pred
 * and rec (1: each contact also goes to the contact record; phase 5 then
 * keeps f_n and f_t in the dead v_n, v_t buffers for phase 6) */
static DEM_ALWAYS_INLINE void pair_loop_hm(dem_world *w, const int periodic, const int uniform, const int pred,
                                           const int rec, double *maxov,
                                           size_t *ncont)
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
    const double dtl = w->cfg.dt;  /* step of the rolling-torque limiter */
    /* uniform (one material): the pair constants are loop invariants instead of per-contact copies */
    const dem_pair *q0 = pt;
    const double u_cn8 = q0->cn8, u_ct8 = q0->mu > 0.0 ? q0->ct8 : 0.0, u_k43 = q0->k43,
                 u_k43m = q0->k43_mind, u_imm = q0->imumind, u_mm = q0->mumind, u_mur = q0->mu_r;
    hm_soa B;
    soa_map(&B, w->scratch, w->capscratch);
    double *restrict Bd0 = B.d0, *restrict Bd1 = B.d1, *restrict Bd2 = B.d2,
           *restrict Bs = B.s, *restrict Bmj = B.mj, *restrict Baj = B.aj,
           *restrict Bdelta = B.delta, *restrict Bdn = B.dn, *restrict Bfcn = B.fcn,
           *restrict Bmeff = B.meff, *restrict Bidt = B.idt, *restrict Bvn = B.vn, *restrict Bvt0 = B.vt0,
           *restrict Bvt1 = B.vt1, *restrict Bvt2 = B.vt2, *restrict Bkt = B.kt,
           *restrict Bct8 = B.ct8, *restrict Bcn8 = B.cn8, *restrict Bg = B.g, *restrict Bsc = B.sc,
           *restrict Bq4 = B.q4, *restrict Bwm2 = B.wm2, *restrict Bcrol = B.crol, *restrict Bmur = B.mur,
           *restrict Bai = B.ai, *restrict Bmi = B.mi, *restrict BIi = B.Ii,
           *restrict Bwr0 = B.wr0, *restrict Bwr1 = B.wr1, *restrict Bwr2 = B.wr2,
           *restrict Bh0 = B.h0, *restrict Bh1 = B.h1, *restrict Bh2 = B.h2,
           *restrict BF0 = B.F0, *restrict BF1 = B.F1, *restrict BF2 = B.F2,
           *restrict BTi0 = B.Ti0, *restrict BTi1 = B.Ti1, *restrict BTi2 = B.Ti2,
           *restrict BTj0 = B.Tj0, *restrict BTj1 = B.Tj1, *restrict BTj2 = B.Tj2;
    double *restrict Bme = B.me;
    const double hp = 0.5 * dt;    /* pred: the last half step */
    int *restrict Bj = B.j, *restrict Bk = B.k, *restrict Bi = B.i;
    double movr = *maxov;
    size_t nct = 0;
    const size_t nrows = w->nrows;
    int nc = 0;
    for (size_t i = 0; i <= nrows; ++i) {
        if (i < nrows) {
            const int k0 = off[i], k1 = off[i + 1];
            if (k0 == k1) continue;
            const double xi0 = x[3 * i], xi1 = x[3 * i + 1], xi2 = x[3 * i + 2];
            const double ai = rad[i], mi = mass[i], Ii = 0.4 * mi * ai * ai;
            const dem_pair *prow = pt + (size_t)mat[i] * nm;
            /* phase 1 (gather): which entries touch; appended to the block */
            for (int k = k0; k < k1; ++k) {
                const int j = nbj[k];
                double d0 = xi0 - x[3 * j], d1 = xi1 - x[3 * j + 1], d2 = xi2 - x[3 * j + 2];
                if (periodic) {
                    const double *sh = w->shift[nbs[k]];
                    d0 += sh[0]; d1 += sh[1]; d2 += sh[2];
                }
                const double aj = rad[j], s = ai + aj;
                const double r2 = d0 * d0 + d1 * d1 + d2 * d2;
                const int touch = r2 < s * s;
                {   /* branch-free: a non-touching entry loses its history and is overwritten next */
                    double *h = nbh + 3 * (size_t)k;
                    const double keep = touch ? 1.0 : 0.0;
                    h[0] *= keep; h[1] *= keep; h[2] *= keep;
                }
                const double mj = mass[j];
                const dem_pair *q = prow + mat[j];
                Bd0[nc] = d0; Bd1[nc] = d1; Bd2[nc] = d2; Bs[nc] = s;
                Bmj[nc] = mj; Baj[nc] = aj;
                if (!uniform) {
                    Bcn8[nc] = q->cn8; Bct8[nc] = q->mu > 0.0 ? q->ct8 : 0.0;
                    Bkt[nc] = q->k43; Bsc[nc] = q->k43_mind; Bidt[nc] = q->imumind; Bg[nc] = q->mumind;
                    Bmur[nc] = q->mu_r;
                }
                Bj[nc] = j; Bk[nc] = k;
                Bai[nc] = ai; Bmi[nc] = mi; BIi[nc] = Ii; Bi[nc] = (int)i;
                nc += touch;
            }
            if (nc < DEM_HM_BLOCK) continue;  /* rows are never split: buffer >= block + longest row */
        }
        if (nc == 0) continue;
        nct += (size_t)nc;
        /* phase 2 (vector): geometry, normal force */
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
            const double k43 = uniform ? u_k43 : Bkt[a];
            Bdelta[a] = delta;
            Bfcn[a] = k43 * sq * delta;
            Bdn[a] = sqrt(meff * sq);
            if (pred) Bme[a] = meff;
            Bmeff[a] = (uniform ? u_mm : Bg[a]) * delta;                 /* delta_t,max = mu mindlin delta */
            Bidt[a] = (uniform ? u_imm : Bidt[a]) * (inv * r * s * msum); /* 1/delta_t,max (mu = 0: 0) */
            Bkt[a] = (uniform ? u_k43m : Bsc[a]) * sq;                    /* mu f_cn / delta_t,max */
        }
        for (int a = 0; a < nc; ++a) {
            const double ov = Bdelta[a];
            if (ov > movr * Bs[a]) movr = ov / Bs[a];
        }
        /* phase 3 (gather): relative velocity, history and relative spin into the buffers */
        for (int a = 0; a < nc; ++a) {
            const int j = Bj[a], ii = Bi[a];
            const double aj = Baj[a], ai = Bai[a];
            const double *wj = om + 3 * j, *vj = v + 3 * j, *wi = om + 3 * ii, *vi = v + 3 * ii;
            const double n[3] = {Bd0[a], Bd1[a], Bd2[a]};
            const double W0 = ai * wi[0] + aj * wj[0], W1 = ai * wi[1] + aj * wj[1],
                         W2 = ai * wi[2] + aj * wj[2];
            const double vc0 = vi[0] - vj[0] - (W1 * n[2] - W2 * n[1]);
            const double vc1 = vi[1] - vj[1] - (W2 * n[0] - W0 * n[2]);
            const double vc2 = vi[2] - vj[2] - (W0 * n[1] - W1 * n[0]);
            const double vn = vc0 * n[0] + vc1 * n[1] + vc2 * n[2];
            Bvn[a] = vn; Bvt0[a] = vc0 - vn * n[0]; Bvt1[a] = vc1 - vn * n[1]; Bvt2[a] = vc2 - vn * n[2];
            const double *h = nbh + 3 * (size_t)Bk[a];
            Bh0[a] = h[0]; Bh1[a] = h[1]; Bh2[a] = h[2];
            const double wr0 = wi[0] - wj[0], wr1 = wi[1] - wj[1], wr2 = wi[2] - wj[2];
            Bwm2[a] = wr0 * wr0 + wr1 * wr1 + wr2 * wr2;
            Bwr0[a] = wr0; Bwr1[a] = wr1; Bwr2[a] = wr2;
        }
        /* phase 4 (vector): tangential law factors, rolling factor */
        DEM_IVDEP
        for (int a = 0; a < nc; ++a) {
            /* history: dem_rotate_history and h += v_t dt, branch-free (the same
               operations where dem_rotate_history does them; selects elsewhere) */
            const double n0 = Bd0[a], n1 = Bd1[a], n2 = Bd2[a];
            double h0 = Bh0[a], h1 = Bh1[a], h2 = Bh2[a];
            const double hn = h0 * n0 + h1 * n1 + h2 * n2;
            const double hh = h0 * h0 + h1 * h1 + h2 * h2;
            double p0 = h0 - hn * n0, p1 = h1 - hn * n1, p2 = h2 - hn * n2;
            const double h2n = p0 * p0 + p1 * p1 + p2 * p2;
            const int resc = hn != 0.0 && h2n > 0.0 && hn * hn > 1e-12 * h2n;
            /* arithmetic guard (no select feeding the division): where resc
               is false the quotient is ~1 or hh / 1, never an overflow */
            const double sres = sqrt(hh / (h2n + (h2n > 0.0 ? 0.0 : 1.0)));
            p0 = resc ? p0 * sres : p0; p1 = resc ? p1 * sres : p1; p2 = resc ? p2 * sres : p2;
            h0 = hn != 0.0 ? p0 : h0; h1 = hn != 0.0 ? p1 : h1; h2 = hn != 0.0 ? p2 : h2;
            h0 += Bvt0[a] * dt; h1 += Bvt1[a] * dt; h2 += Bvt2[a] * dt;
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
            const double wm = sqrt(Bwm2[a]);
            const double wmsafe = wm + (wm > 0.0 ? 0.0 : 1.0);
            const double Ii = BIi[a], Ij = 0.4 * Bmj[a] * Baj[a] * Baj[a], den = dtl * (Ii + Ij);
            const double inv2 = 1.0 / (wmsafe * den);
            const double c1 = (uniform ? u_mur : Bmur[a]) * Bfcn[a] * den * inv2, c2 = Ii * Ij * wmsafe * inv2;
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
            const double ce = -Bkt[a] * Bg[a], cd = -(uniform ? u_ct8 : Bct8[a]) * Bdn[a] * Bq4[a];
            const double ft0 = ce * h0 + cd * Bvt0[a];
            const double ft1 = ce * h1 + cd * Bvt1[a];
            const double ft2 = ce * h2 + cd * Bvt2[a];
            double fn = Bfcn[a] - (uniform ? u_cn8 : Bcn8[a]) * Bdn[a] * Bvn[a];
            if (pred) {   /* damping at the predicted end-of-step velocity (dem_predicted_vn) */
                const double C = (uniform ? u_cn8 : Bcn8[a]) * Bdn[a];
                fn = Bfcn[a] - C * ((Bme[a] * Bvn[a] + hp * Bfcn[a]) / (Bme[a] + hp * C));
            }
            BF0[a] = fn * n0 + ft0; BF1[a] = fn * n1 + ft1; BF2[a] = fn * n2 + ft2;
            if (rec) { Bvn[a] = fn; Bvt0[a] = ft0; Bvt1[a] = ft1; Bvt2[a] = ft2; }
            const double c0 = n1 * ft2 - n2 * ft1, c1 = n2 * ft0 - n0 * ft2, c2 = n0 * ft1 - n1 * ft0;
            const double cr = Bcrol[a];
            const double M0 = cr * Bwr0[a], M1 = cr * Bwr1[a], M2 = cr * Bwr2[a];
            BTi0[a] = M0 - ai * c0; BTi1[a] = M1 - ai * c1; BTi2[a] = M2 - ai * c2;
            BTj0[a] = aj * c0 + M0; BTj1[a] = aj * c1 + M1; BTj2[a] = aj * c2 + M2;
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
        nc = 0;
    }
    *maxov = movr;
    *ncont = nct;
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
    const int u = w->nmat == 1, pred = w->cfg.damping_predicted != 0;
    if (w->crec_now) {
        /* recording: the general (per-contact constants) loop, whose arithmetic
           is that of the uniform one with the same values, so the bits agree */
        if (!pred) { if (per) pair_loop_hm(w, 1, 0, 0, 1, movr, nct); else pair_loop_hm(w, 0, 0, 0, 1, movr, nct); }
        else       { if (per) pair_loop_hm(w, 1, 0, 1, 1, movr, nct); else pair_loop_hm(w, 0, 0, 1, 1, movr, nct); }
    } else if (!pred) {
        if (u) { if (per) pair_loop_hm(w, 1, 1, 0, 0, movr, nct); else pair_loop_hm(w, 0, 1, 0, 0, movr, nct); }
        else   { if (per) pair_loop_hm(w, 1, 0, 0, 0, movr, nct); else pair_loop_hm(w, 0, 0, 0, 0, movr, nct); }
    } else {
        if (u) { if (per) pair_loop_hm(w, 1, 1, 1, 0, movr, nct); else pair_loop_hm(w, 0, 1, 1, 0, movr, nct); }
        else   { if (per) pair_loop_hm(w, 1, 0, 1, 0, movr, nct); else pair_loop_hm(w, 0, 0, 1, 0, movr, nct); }
    }
}

static void contact(const dem_pair *q, double dt, const double n[3], double delta, double d,
                    const double vc[3], double meff, double rstar, double *h,
                    double F[3], double ft[3], double *fel, double *fnout)
{
    hm_force(q, dt, n, delta, d, vc, meff, rstar, h, F, ft, fel, fnout);
}

const dem_law dem_law_hertzMindlin = {
    .name = "hertzMindlin",
    .stiffness_name = "youngs_modulus",
    .stiffness = dem_hm_stiffness,
    .derived = dem_hm_derived,
    .pair = pair,
    .contact_time = contact_time,
    .pair_forces = pair_loops_hm,
    .contact = contact,
};
