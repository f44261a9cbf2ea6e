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

/* contacts processed per block in the phased loop (as hertzMindlin's) */
#define NS_BLOCK 64
_Static_assert(DEM_SCRATCH_EXTRA >= NS_BLOCK, "scratch must hold a block plus the longest row");

#if defined(__GNUC__) && !defined(__clang__)
#define NS_IVDEP _Pragma("GCC ivdep")
#else
#define NS_IVDEP
#endif

/* The pair loop of this law, phased per block of rows like hertzMindlin's
 * (laws/hertzMindlin.c): gathers stay scalar, the arithmetic with square
 * roots and divisions runs in branch-free loops the compiler vectorises.
 * Every value is computed with the same IEEE operations in the same order
 * as contact() above inside dem_pair_loop (contactKernel.h), and the i side
 * of the forces and torques is summed per row as there, so the results are
 * bit-identical to the scalar loop (selects instead of branches; the
 * divisions are guarded arithmetically so that no select feeds them). */
typedef struct {
    double *d0, *d1, *d2, *s, *mj, *aj, *ai, *mi, *Ii;
    double *delta, *fcn, *dn, *meff, *sq;
    double *vn, *vt0, *vt1, *vt2, *h0, *h1, *h2, *wr0, *wr1, *wr2;
    double *F0, *F1, *F2, *ft0, *ft1, *ft2, *M0, *M1, *M2, *fn;
    const dem_pair **q;
    int *j, *k, *i;
} ns_soa;
#define NS_NDOUBLE 34
_Static_assert(NS_NDOUBLE * sizeof(double) + sizeof(void *) + 3 * sizeof(int) <= DEM_SCRATCH_ENTRY,
               "scratch entry too small for the SoA buffers");

static void ns_map(ns_soa *b, void *mem, size_t cap)
{
    double *p = (double *)mem;
    double **f[NS_NDOUBLE] = {&b->d0, &b->d1, &b->d2, &b->s, &b->mj, &b->aj, &b->ai, &b->mi, &b->Ii,
                              &b->delta, &b->fcn, &b->dn, &b->meff, &b->sq,
                              &b->vn, &b->vt0, &b->vt1, &b->vt2, &b->h0, &b->h1, &b->h2,
                              &b->wr0, &b->wr1, &b->wr2, &b->F0, &b->F1, &b->F2,
                              &b->ft0, &b->ft1, &b->ft2, &b->M0, &b->M1, &b->M2, &b->fn};
    for (int a = 0; a < NS_NDOUBLE; ++a) { *f[a] = p; p += cap; }
    b->q = (const dem_pair **)p; p += cap;
    b->j = (int *)p;
    b->k = b->j + cap;
    b->i = b->k + cap;
}

static DEM_ALWAYS_INLINE void pair_loop_ns(dem_world *w, const int periodic, const int uniform, const int pred,
                                           const int rec, double *maxov, size_t *ncont)
{
    const double dt = w->hdt, hp = 0.5 * dt, dtl = w->cfg.dt;
    const int nm = w->nmat;
    const dem_pair *pt = w->pair;
    const double *x = w->x, *v = w->v, *om = w->w, *rad = w->rad, *mass = w->mass;
    const int *mat = w->mat_of;
    double *f = w->f, *t = w->t;
    const int *off = w->nb_off, *nbj = w->nb_j;
    const unsigned char *nbs = w->nb_s;
    double *nbh = w->nb_h;
    const dem_pair *q0 = pt;   /* uniform (one material): the constants are loop invariants */
    const double u_k43 = q0->k43, u_cn8 = q0->cn8, u_cn = q0->cn, u_g8 = q0->g8, u_mu = q0->mu,
                 u_mur = q0->mu_r;
    ns_soa B;
    ns_map(&B, w->scratch, w->capscratch);
    double *restrict Bd0 = B.d0, *restrict Bd1 = B.d1, *restrict Bd2 = B.d2, *restrict Bs = B.s,
           *restrict Bmj = B.mj, *restrict Baj = B.aj, *restrict Bai = B.ai, *restrict Bmi = B.mi,
           *restrict BIi = B.Ii, *restrict Bdelta = B.delta, *restrict Bfcn = B.fcn, *restrict Bdn = B.dn,
           *restrict Bmeff = B.meff, *restrict Bsq = B.sq, *restrict Bvn = B.vn, *restrict Bvt0 = B.vt0,
           *restrict Bvt1 = B.vt1, *restrict Bvt2 = B.vt2, *restrict Bh0 = B.h0, *restrict Bh1 = B.h1,
           *restrict Bh2 = B.h2, *restrict Bwr0 = B.wr0, *restrict Bwr1 = B.wr1, *restrict Bwr2 = B.wr2,
           *restrict BF0 = B.F0, *restrict BF1 = B.F1, *restrict BF2 = B.F2, *restrict Bft0 = B.ft0,
           *restrict Bft1 = B.ft1, *restrict Bft2 = B.ft2, *restrict BM0 = B.M0, *restrict BM1 = B.M1,
           *restrict BM2 = B.M2, *restrict Bfn = B.fn;
    const dem_pair **restrict Bq = B.q;
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
            /* phase 1 (gather): which entries touch, appended to the block */
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
                {   /* a non-touching entry loses its history and is overwritten next */
                    double *h = nbh + 3 * (size_t)k;
                    const double keep = touch ? 1.0 : 0.0;
                    h[0] *= keep; h[1] *= keep; h[2] *= keep;
                }
                Bd0[nc] = d0; Bd1[nc] = d1; Bd2[nc] = d2; Bs[nc] = r2; Bmj[nc] = mass[j]; Baj[nc] = aj;
                Bai[nc] = ai; Bmi[nc] = mi; BIi[nc] = Ii;
                if (!uniform) Bq[nc] = prow + mat[j];
                Bj[nc] = j; Bk[nc] = k; Bi[nc] = (int)i;
                nc += touch;
            }
            if (nc < NS_BLOCK) continue;  /* rows are never split: buffer >= block + longest row */
        }
        if (nc == 0) continue;
        nct += (size_t)nc;
        /* phase 2 (vector): geometry and normal force (Bs holds r^2 until here) */
        NS_IVDEP
        for (int a = 0; a < nc; ++a) {
            const double r = sqrt(Bs[a]), s = Bai[a] + Baj[a], mi = Bmi[a], mj = Bmj[a], msum = mi + mj;
            const double inv = 1.0 / ((r + (r > 0.0 ? 0.0 : 1.0)) * s * msum);
            const double ir = inv * s * msum;
            Bd0[a] *= ir; Bd1[a] *= ir; Bd2[a] *= ir;
            const double delta = s - r;
            const double meff = mi * mj * (inv * r * s);
            const double rstar = Bai[a] * Baj[a] * (inv * r * msum);
            const double sq = sqrt(rstar * delta);
            const double fcn = (uniform ? u_k43 : Bq[a]->k43) * sq * delta;
            Bs[a] = s; Bdelta[a] = delta; Bmeff[a] = meff; Bsq[a] = sq; Bfcn[a] = fcn;
            Bdn[a] = sqrt(meff * sq);
        }
        for (int a = 0; a < nc; ++a) {
            const double ov = Bdelta[a];
            if (ov > movr * Bs[a]) movr = ov / Bs[a];
        }
        /* phase 3 (gather): relative velocity at the contact, history, relative spin */
        for (int a = 0; a < nc; ++a) {
            const int j = Bj[a], ii = Bi[a];
            const double aj = Baj[a], ai = Bai[a];
            const double *wj = om + 3 * j, *vj = v + 3 * j, *wi = om + 3 * ii, *vi = v + 3 * ii;
            const double n0 = Bd0[a], n1 = Bd1[a], n2 = Bd2[a];
            const double W0 = ai * wi[0] + aj * wj[0], W1 = ai * wi[1] + aj * wj[1],
                         W2 = ai * wi[2] + aj * wj[2];
            const double vc0 = vi[0] - vj[0] - (W1 * n2 - W2 * n1);
            const double vc1 = vi[1] - vj[1] - (W2 * n0 - W0 * n2);
            const double vc2 = vi[2] - vj[2] - (W0 * n1 - W1 * n0);
            const double vn = vc0 * n0 + vc1 * n1 + vc2 * n2;
            Bvn[a] = vn; Bvt0[a] = vc0 - vn * n0; Bvt1[a] = vc1 - vn * n1; Bvt2[a] = vc2 - vn * n2;
            const double *h = nbh + 3 * (size_t)Bk[a];
            Bh0[a] = h[0]; Bh1[a] = h[1]; Bh2[a] = h[2];
            Bwr0[a] = wi[0] - wj[0]; Bwr1[a] = wi[1] - wj[1]; Bwr2[a] = wi[2] - wj[2];
        }
        /* phase 4 (vector): normal force, history, tangential spring with its
           Coulomb limit, rolling torque, total force */
        NS_IVDEP
        for (int a = 0; a < nc; ++a) {
            const double n0 = Bd0[a], n1 = Bd1[a], n2 = Bd2[a], vt0 = Bvt0[a], vt1 = Bvt1[a], vt2 = Bvt2[a];
            const double fcn = Bfcn[a], meff = Bmeff[a], dn = Bdn[a];
            const double cn8 = uniform ? u_cn8 : Bq[a]->cn8;
            double fn = fcn - cn8 * dn * Bvn[a];
            if (pred) {
                const double C = cn8 * dn;
                fn = fcn - C * ((meff * Bvn[a] + hp * fcn) / (meff + hp * C));
            }
            /* dem_rotate_history, branch-free */
            double h0 = Bh0[a], h1 = Bh1[a], h2 = Bh2[a];
            const double hn = h0 * n0 + h1 * n1 + h2 * n2;
            const double hh = h0 * h0 + h1 * h1 + h2 * h2;
            double p0 = h0 - hn * n0, p1 = h1 - hn * n1, p2 = h2 - hn * n2;
            const double h2n = p0 * p0 + p1 * p1 + p2 * p2;
            const int resc = hn != 0.0 && h2n > 0.0 && hn * hn > 1e-12 * h2n;
            const double sres = sqrt(hh / (h2n + (h2n > 0.0 ? 0.0 : 1.0)));
            p0 = resc ? p0 * sres : p0; p1 = resc ? p1 * sres : p1; p2 = resc ? p2 * sres : p2;
            h0 = hn != 0.0 ? p0 : h0; h1 = hn != 0.0 ? p1 : h1; h2 = hn != 0.0 ? p2 : h2;
            h0 += vt0 * dt; h1 += vt1 * dt; h2 += vt2 * dt;
            /* spring and damping, Coulomb limit */
            const double kt = (uniform ? u_g8 : Bq[a]->g8) * Bsq[a];
            const double ct = (uniform ? u_cn : Bq[a]->cn) * sqrt(meff * kt);
            double ft0 = -kt * h0 - ct * vt0, ft1 = -kt * h1 - ct * vt1, ft2 = -kt * h2 - ct * vt2;
            const double ftm = sqrt(ft0 * ft0 + ft1 * ft1 + ft2 * ft2);
            const double lim = (uniform ? u_mu : Bq[a]->mu) * fcn;
            const int slide = ftm > lim;
            const double sc = lim / (ftm + (ftm > 0.0 ? 0.0 : 1.0));
            ft0 = slide ? ft0 * sc : ft0; ft1 = slide ? ft1 * sc : ft1; ft2 = slide ? ft2 * sc : ft2;
            const double ikt = kt + (kt > 0.0 ? 0.0 : 1.0);
            const double g0 = -(ft0 + ct * vt0) / ikt, g1 = -(ft1 + ct * vt1) / ikt, g2 = -(ft2 + ct * vt2) / ikt;
            h0 = slide ? g0 : h0; h1 = slide ? g1 : h1; h2 = slide ? g2 : h2;
            const int fric = (uniform ? u_mu : Bq[a]->mu) > 0.0 && Bdelta[a] > 0.0;
            h0 = fric ? h0 : 0.0; h1 = fric ? h1 : 0.0; h2 = fric ? h2 : 0.0;
            ft0 = fric ? ft0 : 0.0; ft1 = fric ? ft1 : 0.0; ft2 = fric ? ft2 : 0.0;
            Bh0[a] = h0; Bh1[a] = h1; Bh2[a] = h2;
            Bft0[a] = ft0; Bft1[a] = ft1; Bft2[a] = ft2;
            BF0[a] = fn * n0 + ft0; BF1[a] = fn * n1 + ft1; BF2[a] = fn * n2 + ft2;
            Bfn[a] = fn;
            /* rolling (dem_rolling): c = -min(mu_r f_cn, wm Ii Ij / (dt (Ii + Ij))) / wm */
            const double wr0 = Bwr0[a], wr1 = Bwr1[a], wr2 = Bwr2[a];
            const double wm2 = wr0 * wr0 + wr1 * wr1 + wr2 * wr2;
            const double wm = sqrt(wm2), m = (uniform ? u_mur : Bq[a]->mu_r) * fcn;
            const double Ii = BIi[a], Ij = 0.4 * Bmj[a] * Baj[a] * Baj[a];
            const double num = Ii * Ij, den = dtl * (Ii + Ij);
            const double inv = 1.0 / ((wm + (wm > 0.0 ? 0.0 : 1.0)) * (den + (den > 0.0 ? 0.0 : 1.0)));
            const double c = m * den > wm * num ? -num * wm * inv : -m * den * inv;
            BM0[a] = wm2 <= 0.0 ? 0.0 : c * wr0; BM1[a] = wm2 <= 0.0 ? 0.0 : c * wr1;
            BM2[a] = wm2 <= 0.0 ? 0.0 : c * wr2;
        }
        /* phase 5 (scatter): history; forces and torques, the i side summed per row */
        {
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
                if ((uniform ? u_mur : Bq[a]->mu_r) > 0.0) {
                    const double M0 = BM0[a], M1 = BM1[a], M2 = BM2[a];
                    ti0 += M0; ti1 += M1; ti2 += M2;
                    t[3 * j] -= M0; t[3 * j + 1] -= M1; t[3 * j + 2] -= M2;
                }
            }
            f[3 * row] += fi0; f[3 * row + 1] += fi1; f[3 * row + 2] += fi2;
            t[3 * row] += ti0; t[3 * row + 1] += ti1; t[3 * row + 2] += ti2;
        }
        nc = 0;
    }
    *maxov = movr;
    *ncont = nct;
}

/* compiled for AVX-512, AVX2 and generic x86-64, chosen at load time, all
 * bit-identical (DEM_MULTIVERSION, dem_private.h; as hertzMindlin's) */
DEM_MULTIVERSION __attribute__((noinline))
static void pair_forces(dem_world *w, int per, double *movr, size_t *nct)
{
    const int u = w->nmat == 1, pred = w->cfg.damping_predicted != 0;
    if (w->crec_now) {
        if (!pred) { if (per) pair_loop_ns(w, 1, 0, 0, 1, movr, nct); else pair_loop_ns(w, 0, 0, 0, 1, movr, nct); }
        else       { if (per) pair_loop_ns(w, 1, 0, 1, 1, movr, nct); else pair_loop_ns(w, 0, 0, 1, 1, movr, nct); }
    } else if (!pred) {
        if (u) { if (per) pair_loop_ns(w, 1, 1, 0, 0, movr, nct); else pair_loop_ns(w, 0, 1, 0, 0, movr, nct); }
        else   { if (per) pair_loop_ns(w, 1, 0, 0, 0, movr, nct); else pair_loop_ns(w, 0, 0, 0, 0, movr, nct); }
    } else {
        if (u) { if (per) pair_loop_ns(w, 1, 1, 1, 0, movr, nct); else pair_loop_ns(w, 0, 1, 1, 0, movr, nct); }
        else   { if (per) pair_loop_ns(w, 1, 0, 1, 0, movr, nct); else pair_loop_ns(w, 0, 0, 1, 0, movr, nct); }
    }
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
