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
#include "wallLoop.h"

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

/* The pair loop of this law: the phased skeleton of contactKernel.h (as
 * hertzMindlin's).  Every value is computed with the same IEEE operations
 * in the same order as contact() above inside dem_pair_loop
 * (contactKernel.h), and the i side of the forces and torques is summed per
 * row as there, so the results are bit-identical to the scalar loop
 * (selects instead of branches; the divisions are guarded arithmetically so
 * that no select feeds them). */
typedef struct {
    double *fcn, *dn, *meff, *sq;
    double *F0, *F1, *F2, *ft0, *ft1, *ft2, *M0, *M1, *M2, *fn;
    /* uniform (one material): the pair constants as loop invariants */
    double u_k43, u_cn8, u_cn, u_g8, u_mu, u_mur;
} ns_law;
#define NS_NDOUBLE 14
DEM_PHASED_FITS(NS_NDOUBLE);

/* the law's buffers and the constants of the one pair (uniform) */
static DEM_ALWAYS_INLINE void ns_init(const dem_world *w, void *vL, double *p, size_t cap)
{
    ns_law *b = vL;
    const dem_pair *q0 = w->pair;
    b->u_k43 = q0->k43; b->u_cn8 = q0->cn8; b->u_cn = q0->cn; b->u_g8 = q0->g8; b->u_mu = q0->mu;
    b->u_mur = q0->mu_r;
    double **f[NS_NDOUBLE] = {&b->fcn, &b->dn, &b->meff, &b->sq, &b->F0, &b->F1, &b->F2,
                              &b->ft0, &b->ft1, &b->ft2, &b->M0, &b->M1, &b->M2, &b->fn};
    dem_phased_assign(f, NS_NDOUBLE, p, cap);
}

/* phase 1, several materials: the pair per contact */
static DEM_ALWAYS_INLINE void ns_consts(const dem_phased_buf *B, void *vL, int a, const dem_pair *q)
{
    (void)vL;
    B->q[a] = q;
}

/* phase 2 (vector): geometry and normal force */
static DEM_ALWAYS_INLINE void ns_geometry(const dem_world *w, const dem_phased_buf *B, void *vL, int nc,
                                          const int uniform, const int pred)
{
    const ns_law *L = vL;
    (void)w; (void)pred;
    double *restrict Bd0 = B->d0, *restrict Bd1 = B->d1, *restrict Bd2 = B->d2, *restrict Bdelta = B->delta;
    const double *restrict Bs = B->s, *restrict Bmi = B->mi, *restrict Bmj = B->mj, *restrict Bai = B->ai,
                 *restrict Baj = B->aj;
    const dem_pair **restrict Bq = B->q;
    double *restrict Bfcn = L->fcn, *restrict Bdn = L->dn, *restrict Bmeff = L->meff, *restrict Bsq = L->sq;
    DEM_IVDEP
    for (int a = 0; a < nc; ++a) {
        const double r = sqrt(Bd0[a] * Bd0[a] + Bd1[a] * Bd1[a] + Bd2[a] * Bd2[a]);
        const double s = Bs[a], mi = Bmi[a], mj = Bmj[a], msum = mi + mj;
        const double inv = 1.0 / ((r + (r > 0.0 ? 0.0 : 1.0)) * s * msum);
        const double ir = inv * s * msum;
        Bd0[a] *= ir; Bd1[a] *= ir; Bd2[a] *= ir;
        const double delta = s - r;
        const double meff = mi * mj * (inv * r * s);
        const double rstar = Bai[a] * Baj[a] * (inv * r * msum);
        const double sq = sqrt(rstar * delta);
        const double fcn = (uniform ? L->u_k43 : Bq[a]->k43) * sq * delta;
        Bdelta[a] = delta; Bmeff[a] = meff; Bsq[a] = sq; Bfcn[a] = fcn;
        Bdn[a] = sqrt(meff * sq);
    }
}

/* phases 4 and 5: normal force, history, tangential spring with its
 * Coulomb limit, rolling torque, total force; scatter with the i side
 * summed per row */
static DEM_ALWAYS_INLINE void ns_forces(dem_world *w, const dem_phased_buf *B, void *vL, int nc,
                                        const int uniform, const int pred, const int rec)
{
    const ns_law *L = vL;
    const double dt = w->hdt, hp = 0.5 * dt, dtl = w->cfg.dt;
    double *f = w->f, *t = w->t, *nbh = w->nb_h;
    const double *restrict Bd0 = B->d0, *restrict Bd1 = B->d1, *restrict Bd2 = B->d2, *restrict Bai = B->ai,
                 *restrict Baj = B->aj, *restrict Bmj = B->mj, *restrict BIi = B->Ii, *restrict Bdelta = B->delta,
                 *restrict Bvn = B->vn, *restrict Bvt0 = B->vt0, *restrict Bvt1 = B->vt1, *restrict Bvt2 = B->vt2,
                 *restrict Bwr0 = B->wr0, *restrict Bwr1 = B->wr1, *restrict Bwr2 = B->wr2;
    double *restrict Bh0 = B->h0, *restrict Bh1 = B->h1, *restrict Bh2 = B->h2;
    const dem_pair **restrict Bq = B->q;
    const int *restrict Bj = B->j, *restrict Bk = B->k, *restrict Bi = B->i;
    const double *restrict Bfcn = L->fcn, *restrict Bdn = L->dn, *restrict Bmeff = L->meff, *restrict Bsq = L->sq;
    double *restrict BF0 = L->F0, *restrict BF1 = L->F1, *restrict BF2 = L->F2, *restrict Bft0 = L->ft0,
           *restrict Bft1 = L->ft1, *restrict Bft2 = L->ft2, *restrict BM0 = L->M0, *restrict BM1 = L->M1,
           *restrict BM2 = L->M2, *restrict Bfn = L->fn;
    /* phase 4 (vector) */
    DEM_IVDEP
    for (int a = 0; a < nc; ++a) {
        const double n0 = Bd0[a], n1 = Bd1[a], n2 = Bd2[a], vt0 = Bvt0[a], vt1 = Bvt1[a], vt2 = Bvt2[a];
        const double fcn = Bfcn[a], meff = Bmeff[a], dn = Bdn[a];
        const double cn8 = uniform ? L->u_cn8 : Bq[a]->cn8;
        double fn = fcn - cn8 * dn * Bvn[a];
        if (pred) {
            const double C = cn8 * dn;
            fn = fcn - C * ((meff * Bvn[a] + hp * fcn) / (meff + hp * C));
        }
        /* history: rotated, h += v_t dt */
        double hs[3] = {Bh0[a], Bh1[a], Bh2[a]};
        dem_history_step(n0, n1, n2, vt0, vt1, vt2, dt, hs);
        double h0 = hs[0], h1 = hs[1], h2 = hs[2];
        /* spring and damping, Coulomb limit */
        const double kt = (uniform ? L->u_g8 : Bq[a]->g8) * Bsq[a];
        const double ct = (uniform ? L->u_cn : Bq[a]->cn) * sqrt(meff * kt);
        double ft0 = -kt * h0 - ct * vt0, ft1 = -kt * h1 - ct * vt1, ft2 = -kt * h2 - ct * vt2;
        const double ftm = sqrt(ft0 * ft0 + ft1 * ft1 + ft2 * ft2);
        const double lim = (uniform ? L->u_mu : Bq[a]->mu) * fcn;
        const int slide = ftm > lim;
        const double sc = lim / (ftm + (ftm > 0.0 ? 0.0 : 1.0));
        ft0 = slide ? ft0 * sc : ft0; ft1 = slide ? ft1 * sc : ft1; ft2 = slide ? ft2 * sc : ft2;
        const double ikt = kt + (kt > 0.0 ? 0.0 : 1.0);
        const double g0 = -(ft0 + ct * vt0) / ikt, g1 = -(ft1 + ct * vt1) / ikt, g2 = -(ft2 + ct * vt2) / ikt;
        h0 = slide ? g0 : h0; h1 = slide ? g1 : h1; h2 = slide ? g2 : h2;
        const int fric = (uniform ? L->u_mu : Bq[a]->mu) > 0.0 && Bdelta[a] > 0.0;
        h0 = fric ? h0 : 0.0; h1 = fric ? h1 : 0.0; h2 = fric ? h2 : 0.0;
        ft0 = fric ? ft0 : 0.0; ft1 = fric ? ft1 : 0.0; ft2 = fric ? ft2 : 0.0;
        Bh0[a] = h0; Bh1[a] = h1; Bh2[a] = h2;
        Bft0[a] = ft0; Bft1[a] = ft1; Bft2[a] = ft2;
        BF0[a] = fn * n0 + ft0; BF1[a] = fn * n1 + ft1; BF2[a] = fn * n2 + ft2;
        Bfn[a] = fn;
        /* rolling (dem_rolling): c = -min(mu_r f_cn, wm Ii Ij / (dt (Ii + Ij))) / wm */
        /* uniform == 2 (mu_r = 0): no relative spin was gathered, no torque */
        const double wr0 = uniform != 2 ? Bwr0[a] : 0.0, wr1 = uniform != 2 ? Bwr1[a] : 0.0,
                     wr2 = uniform != 2 ? Bwr2[a] : 0.0;
        const double wm2 = wr0 * wr0 + wr1 * wr1 + wr2 * wr2;
        const double wm = sqrt(wm2), m = (uniform ? L->u_mur : Bq[a]->mu_r) * fcn;
        const double Ii = BIi[a], Ij = 0.4 * Bmj[a] * Baj[a] * Baj[a];
        const double num = Ii * Ij, den = dtl * (Ii + Ij);
        const double inv = 1.0 / ((wm + (wm > 0.0 ? 0.0 : 1.0)) * (den + (den > 0.0 ? 0.0 : 1.0)));
        const double c = m * den > wm * num ? -num * wm * inv : -m * den * inv;
        BM0[a] = wm2 <= 0.0 ? 0.0 : c * wr0; BM1[a] = wm2 <= 0.0 ? 0.0 : c * wr1;
        BM2[a] = wm2 <= 0.0 ? 0.0 : c * wr2;
    }
    /* phase 5 (scatter): history; forces and torques, the i side summed per row */
    int row = Bi[0];
    double fi0 = 0, fi1 = 0, fi2 = 0, ti0 = 0, ti1 = 0, ti2 = 0;
    for (int a = 0; a < nc; ++a) {
        const int j = Bj[a], ii = Bi[a];
        if (ii != row) {
            f[3 * row] += fi0; f[3 * row + 1] += fi1; f[3 * row + 2] += fi2;
            t[3 * row] += ti0; t[3 * row + 1] += ti1; t[3 * row + 2] += ti2;
            fi0 = fi1 = fi2 = ti0 = ti1 = ti2 = 0.0;
            row = ii;
        }
        double *h = nbh + 3 * (size_t)Bk[a];
        h[0] = Bh0[a]; h[1] = Bh1[a]; h[2] = Bh2[a];
        const double F0 = BF0[a], F1 = BF1[a], F2 = BF2[a];
        const double n0 = Bd0[a], n1 = Bd1[a], n2 = Bd2[a];
        const double ft0 = Bft0[a], ft1 = Bft1[a], ft2 = Bft2[a];
        const double ai = Bai[a], aj = Baj[a];
        if (rec) {
            const double n[3] = {n0, n1, n2}, ft[3] = {ft0, ft1, ft2};
            dem_record_contact(w, (size_t)ii, j, 0, (size_t)ii >= w->n || (size_t)j >= w->n, Bdelta[a], n,
                               Bfn[a], ft);
        }
        fi0 += F0; fi1 += F1; fi2 += F2;
        f[3 * j] -= F0; f[3 * j + 1] -= F1; f[3 * j + 2] -= F2;
        const double c0 = n1 * ft2 - n2 * ft1, c1 = n2 * ft0 - n0 * ft2, c2 = n0 * ft1 - n1 * ft0;
        ti0 -= ai * c0; ti1 -= ai * c1; ti2 -= ai * c2;
        t[3 * j] -= aj * c0; t[3 * j + 1] -= aj * c1; t[3 * j + 2] -= aj * c2;
        if ((uniform ? L->u_mur : Bq[a]->mu_r) > 0.0) {
            const double M0 = BM0[a], M1 = BM1[a], M2 = BM2[a];
            ti0 += M0; ti1 += M1; ti2 += M2;
            t[3 * j] -= M0; t[3 * j + 1] -= M1; t[3 * j + 2] -= M2;
        }
    }
    f[3 * row] += fi0; f[3 * row + 1] += fi1; f[3 * row + 2] += fi2;
    t[3 * row] += ti0; t[3 * row + 1] += ti1; t[3 * row + 2] += ti2;
}

static DEM_ALWAYS_INLINE void pair_loop_ns(dem_world *w, const int periodic, const int uniform, const int pred,
                                           const int rec, double *maxov, size_t *ncont)
{
    ns_law L;
    dem_phased_loop(w, &L, NS_NDOUBLE, ns_init, ns_consts, ns_geometry, ns_forces, periodic, uniform, pred, rec,
                    maxov, ncont);
}

/* compiled for AVX-512, AVX2 and generic x86-64, chosen at load time, all
 * bit-identical (DEM_MULTIVERSION, dem_private.h; as hertzMindlin's) */
DEM_MULTIVERSION __attribute__((noinline))
static void pair_forces(dem_world *w, int per, double *movr, size_t *nct)
{
    DEM_PHASED_DISPATCH(pair_loop_ns, w, per, movr, nct);
}

/* contact() over a block of wall contacts, branch-free: the spring's force,
 * and its Coulomb-limited form, each with contact()'s IEEE operations and
 * selected, so the results are contact()'s bit for bit.  The guards of the
 * divisions (|f_t| and k_t where they are 0) go through memory to a second
 * loop, as in hertzMindlin's wall block (tests/dem/test_fpe.c). */
static DEM_ALWAYS_INLINE void ns_wall_block(const dem_world *w, dem_wall_block *b, int nc)
{
    const double dt = w->hdt, hp = 0.5 * dt;
    double k43[DEM_WALL_BLOCK], cn8[DEM_WALL_BLOCK], pred[DEM_WALL_BLOCK], mu[DEM_WALL_BLOCK],
        g8[DEM_WALL_BLOCK], cn[DEM_WALL_BLOCK];
    double ctA[DEM_WALL_BLOCK], e0A[DEM_WALL_BLOCK], e1A[DEM_WALL_BLOCK], e2A[DEM_WALL_BLOCK],
        ftmA[DEM_WALL_BLOCK], ftmsA[DEM_WALL_BLOCK], ktsA[DEM_WALL_BLOCK], springA[DEM_WALL_BLOCK];
    for (int a = 0; a < nc; ++a) {
        const dem_pair *q = b->q[a];
        k43[a] = q->k43; cn8[a] = q->cn8; pred[a] = q->pred; mu[a] = q->mu; g8[a] = q->g8; cn[a] = q->cn;
    }
    /* normal force, v_t (into vc), history advanced (into h), the spring's force and guards */
    DEM_IVDEP
    for (int a = 0; a < nc; ++a) {
        double sq, dn;
        dem_hertz_block_start(b, a, k43[a], cn8[a], pred[a], dt, hp, &sq, &dn);
        const double kt = g8[a] * sq, ct = cn[a] * sqrt(b->meff[a] * kt);
        const double vt0 = b->vc0[a], vt1 = b->vc1[a], vt2 = b->vc2[a];
        const double e0 = -kt * b->h0[a] - ct * vt0, e1 = -kt * b->h1[a] - ct * vt1, e2 = -kt * b->h2[a] - ct * vt2;
        const double ftm = sqrt(e0 * e0 + e1 * e1 + e2 * e2);
        ctA[a] = ct; e0A[a] = e0; e1A[a] = e1; e2A[a] = e2; ftmA[a] = ftm;
        springA[a] = mu[a] > 0.0 && b->delta[a] > 0.0 ? 1.0 : 0.0;
        ktsA[a] = kt + (kt > 0.0 ? 0.0 : 1.0);
        /* |f_t| guarded where it is 0 (its quotient is used only beyond the limit, |f_t| > 0) */
        ftmsA[a] = ftm + (ftm > 0.0 ? 0.0 : 1.0);
    }
    /* the Coulomb limit, selected */
    DEM_IVDEP
    for (int a = 0; a < nc; ++a) {
        const double vt0 = b->vc0[a], vt1 = b->vc1[a], vt2 = b->vc2[a];
        const double e0 = e0A[a], e1 = e1A[a], e2 = e2A[a], ct = ctA[a], kts = ktsA[a];
        const double lim = mu[a] * b->fel[a];
        const int spring = springA[a] > 0.0, over = ftmA[a] > lim;
        const double s = lim / ftmsA[a];
        const double l0 = e0 * s, l1 = e1 * s, l2 = e2 * s;
        const double lh0 = -(l0 + ct * vt0) / kts, lh1 = -(l1 + ct * vt1) / kts, lh2 = -(l2 + ct * vt2) / kts;
        const double ft0 = !spring ? 0.0 : over ? l0 : e0, ft1 = !spring ? 0.0 : over ? l1 : e1,
                     ft2 = !spring ? 0.0 : over ? l2 : e2;
        b->h0[a] = !spring ? 0.0 : over ? lh0 : b->h0[a];
        b->h1[a] = !spring ? 0.0 : over ? lh1 : b->h1[a];
        b->h2[a] = !spring ? 0.0 : over ? lh2 : b->h2[a];
        b->ft0[a] = ft0; b->ft1[a] = ft1; b->ft2[a] = ft2;
    }
}

DEM_WALL_FORCES_BLOCKED(wall_forces, contact, ns_wall_block)

const dem_law dem_law_hertzMindlinNoSlip = {
    .name = "hertzMindlinNoSlip",
    .stiffness_name = "youngs_modulus",
    .stiffness = dem_hm_stiffness,
    .derived = dem_hm_derived,
    .pair = pair,
    .contact_time = contact_time,
    .pair_forces = pair_forces,
    .wall_forces = wall_forces,
};
