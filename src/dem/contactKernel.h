/*---------------------------------------------------------------------------*\
  demFoam DEM core - pieces shared by the contact laws (laws/) and the
  wall loop (contact.c): history rotation, rolling friction, the scalar pair
  loop, the skeleton of the phased pair loops.
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

/* The Hertz normal force of hertzMindlin and hertzMindlinNoSlip for the
 * branch-free block kernels (wallLoop.h): sqrt(R* delta), f_cn,
 * sqrt(m* sqrt(R* delta)) and f_n, with the damping at the predicted
 * velocity where pred > 0, by the IEEE operations of the laws' one-contact
 * kernels (hp: half the step). */
static DEM_ALWAYS_INLINE void dem_hertz_normal_select(double k43, double cn8, double pred, double rstar,
                                                      double delta, double meff, double vn, double hp,
                                                      double *sq, double *fcn, double *dn, double *fn)
{
    const double s = sqrt(rstar * delta), fc = k43 * s * delta, d = sqrt(meff * s), C = cn8 * d;
    const double fn0 = fc - C * vn;
    const double fnp = fc - C * dem_predicted_vn(vn, fc, C, meff, hp);
    *sq = s; *fcn = fc; *dn = d;
    *fn = pred > 0.0 ? fnp : fn0;
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

/* x_i - x_j of list entry k with partner j, plus its periodic image shift */
static DEM_ALWAYS_INLINE void dem_pair_offset(const dem_world *w, const double *x, const unsigned char *nbs,
                                              double xi0, double xi1, double xi2, size_t j, int k,
                                              const int periodic, double d[3])
{
    d[0] = xi0 - x[3 * j]; d[1] = xi1 - x[3 * j + 1]; d[2] = xi2 - x[3 * j + 2];
    if (periodic) {
        const double *sh = w->shift[nbs[k]];
        d[0] += sh[0]; d[1] += sh[1]; d[2] += sh[2];
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
            double d[3];
            dem_pair_offset(w, x, nbs, xi0, xi1, xi2, j, k, periodic, d);
            const double d0 = d[0], d1 = d[1], d2 = d[2];
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

/*--- the phased pair loop --------------------------------------------------*/
/* The skeleton of the phased pair loops (hertzMindlin, hertzMindlinNoSlip).
 * The touching contacts of whole rows are collected into structure-of-arrays
 * buffers (phase 1, gather) until a block is full, then each phase runs over
 * all of them: the law's geometry and normal force (vector), the largest
 * overlap, the relative velocity, history and spin (gather), and the law's
 * forces, torques and scatter.  Gathers stay scalar, while the arithmetic
 * with square roots and divisions runs in branch-free loops the compiler
 * vectorises, so these long-latency operations overlap instead of forming
 * one dependent chain per contact. */

/* contacts processed per block */
#define DEM_PHASED_BLOCK 64
_Static_assert(DEM_SCRATCH_EXTRA >= DEM_PHASED_BLOCK, "scratch must hold a block plus the longest row");

/* independent iterations (distinct SoA buffers): let GCC vectorise */
#if defined(__GNUC__) && !defined(__clang__)
#define DEM_IVDEP _Pragma("GCC ivdep")
#else
#define DEM_IVDEP
#endif

/* The buffers the skeleton fills; a law's own ones follow them in w->scratch. */
typedef struct {
    double *d0, *d1, *d2;               /* x_i - x_j (+ periodic shift); the law's geometry makes it n */
    double *s, *mj, *aj, *ai, *mi, *Ii; /* a_i + a_j, m_j, a_j, a_i, m_i, I_i */
    double *delta;                      /* overlap (the law's geometry) */
    double *vn, *vt0, *vt1, *vt2;       /* v_n, v_t (dem_phased_kinematics) */
    double *h0, *h1, *h2;               /* tangential history (dem_phased_kinematics) */
    double *wr0, *wr1, *wr2;            /* w_i - w_j (dem_phased_kinematics) */
    const dem_pair **q;                 /* pair constants, for a law that keeps them per contact */
    int *j, *k, *i;                     /* partner, list entry, row */
} dem_phased_buf;
#define DEM_PHASED_NDOUBLE 20

/* A law with nlaw buffers of its own fits into an entry of w->scratch. */
#define DEM_PHASED_FITS(nlaw) _Static_assert((DEM_PHASED_NDOUBLE + (nlaw)) * sizeof(double) + sizeof(void *) + \
                                             3 * sizeof(int) <= DEM_SCRATCH_ENTRY,                           \
                                             "scratch entry too small for the SoA buffers")

/* n buffers of cap entries from p on: *f[0] = p, *f[1] = p + cap, ... */
static inline double *dem_phased_assign(double **const *f, int n, double *p, size_t cap)
{
    for (int a = 0; a < n; ++a) { *f[a] = p; p += cap; }
    return p;
}

/* The skeleton's buffers in mem (cap entries each), then nlaw buffers of the
 * law (returned), then q, j, k, i. */
static inline double *dem_phased_map(dem_phased_buf *b, void *mem, size_t cap, size_t nlaw)
{
    double *p = (double *)mem;
    double **f[DEM_PHASED_NDOUBLE] = {&b->d0, &b->d1, &b->d2, &b->s, &b->mj, &b->aj, &b->ai, &b->mi, &b->Ii,
                                      &b->delta, &b->vn, &b->vt0, &b->vt1, &b->vt2, &b->h0, &b->h1, &b->h2,
                                      &b->wr0, &b->wr1, &b->wr2};
    double *law = dem_phased_assign(f, DEM_PHASED_NDOUBLE, p, cap);
    p = law + nlaw * cap;
    b->q = (const dem_pair **)p; p += cap;
    b->j = (int *)p;
    b->k = b->j + cap;
    b->i = b->k + cap;
    return law;
}

/* dem_rotate_history and h += v_t dt for the vectorised phases, branch-free:
 * the same operations where dem_rotate_history does them, selects elsewhere.
 * The guard of the division is arithmetic (no select feeds it): where h is
 * not rescaled the quotient is ~1 or hh / 1, never an overflow. */
static DEM_ALWAYS_INLINE void dem_history_step(double n0, double n1, double n2, double vt0, double vt1, double vt2,
                                               double dt, double h[3])
{
    double h0 = h[0], h1 = h[1], h2 = h[2];
    const double hn = h0 * n0 + h1 * n1 + h2 * n2;
    const double hh = h0 * h0 + h1 * h1 + h2 * h2;
    double p0 = h0 - hn * n0, p1 = h1 - hn * n1, p2 = h2 - hn * n2;
    const double h2n = p0 * p0 + p1 * p1 + p2 * p2;
    const int resc = hn != 0.0 && h2n > 0.0 && hn * hn > 1e-12 * h2n;
    const double sres = sqrt(hh / (h2n + (h2n > 0.0 ? 0.0 : 1.0)));
    p0 = resc ? p0 * sres : p0; p1 = resc ? p1 * sres : p1; p2 = resc ? p2 * sres : p2;
    h0 = hn != 0.0 ? p0 : h0; h1 = hn != 0.0 ? p1 : h1; h2 = hn != 0.0 ? p2 : h2;
    h[0] = h0 + vt0 * dt; h[1] = h1 + vt1 * dt; h[2] = h2 + vt2 * dt;
}

/* Phase 3 (gather): relative velocity at the contact (n in d0..d2), its
 * normal and tangential parts, the history and (roll) the relative spin. */
static DEM_ALWAYS_INLINE void dem_phased_kinematics(const dem_world *w, const dem_phased_buf *B, int nc,
                                                    const int roll)
{
    const double *v = w->v, *om = w->w, *nbh = w->nb_h;
    const double *restrict Bd0 = B->d0, *restrict Bd1 = B->d1, *restrict Bd2 = B->d2,
                 *restrict Bai = B->ai, *restrict Baj = B->aj;
    double *restrict Bvn = B->vn, *restrict Bvt0 = B->vt0, *restrict Bvt1 = B->vt1, *restrict Bvt2 = B->vt2,
           *restrict Bh0 = B->h0, *restrict Bh1 = B->h1, *restrict Bh2 = B->h2,
           *restrict Bwr0 = B->wr0, *restrict Bwr1 = B->wr1, *restrict Bwr2 = B->wr2;
    const int *restrict Bj = B->j, *restrict Bk = B->k, *restrict Bi = B->i;
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
        if (roll) { Bwr0[a] = wi[0] - wj[0]; Bwr1[a] = wi[1] - wj[1]; Bwr2[a] = wi[2] - wj[2]; }
    }
}

/* What a law gives the skeleton (always-inline functions, constants at each
 * call site, so that every call is inlined and specialised):
 *   init(w, L, buf, cap): its buffers (buf: nlaw of cap entries) and
 *       constants into its struct L;
 *   consts(B, L, a, q): phase 1 of a loop with per-contact constants
 *       (!uniform): pair q's constants into slot a of the law's buffers L;
 *   geometry(w, B, L, nc, uniform, pred): phase 2, from d0..d2 and s the
 *       unit normal (into d0..d2), delta and the normal force;
 *   forces(w, B, L, nc, uniform, pred, rec): the tangential law, forces and
 *       torques, history, force scatter (rec: each contact also to the record). */
typedef void (*dem_phased_init_fn)(const dem_world *w, void *L, double *buf, size_t cap);
typedef void (*dem_phased_consts_fn)(const dem_phased_buf *B, void *L, int a, const dem_pair *q);
typedef void (*dem_phased_geometry_fn)(const dem_world *w, const dem_phased_buf *B, void *L, int nc,
                                       int uniform, int pred);
typedef void (*dem_phased_forces_fn)(dem_world *w, const dem_phased_buf *B, void *L, int nc, int uniform,
                                     int pred, int rec);

/* The phased loop over the neighbour list (always inlined: each call site
 * is specialised for periodic/uniform/pred/rec). */
static DEM_ALWAYS_INLINE void dem_phased_loop(dem_world *w, void *L, size_t nlaw, dem_phased_init_fn init,
                                              dem_phased_consts_fn consts, dem_phased_geometry_fn geometry,
                                              dem_phased_forces_fn forces, const int periodic, const int uniform,
                                              const int pred, const int rec, double *maxov, size_t *ncont)
{
    dem_phased_buf Bb;
    const dem_phased_buf *B = &Bb;
    init(w, L, dem_phased_map(&Bb, w->scratch, w->capscratch, nlaw), w->capscratch);
    const int nm = w->nmat;
    const dem_pair *pt = w->pair;
    const double *x = w->x, *rad = w->rad, *mass = w->mass;
    const int *mat = w->mat_of;
    const int *off = w->nb_off, *nbj = w->nb_j;
    const unsigned char *nbs = w->nb_s;
    double *nbh = w->nb_h;
    double *restrict Bd0 = B->d0, *restrict Bd1 = B->d1, *restrict Bd2 = B->d2, *restrict Bs = B->s,
           *restrict Bmj = B->mj, *restrict Baj = B->aj, *restrict Bai = B->ai, *restrict Bmi = B->mi,
           *restrict BIi = B->Ii;
    const double *restrict Bdelta = B->delta;
    int *restrict Bj = B->j, *restrict Bk = B->k, *restrict Bi = B->i;
    double movr = *maxov;
    size_t nct = 0;
    const size_t nrows = w->nrows;
    int nc = 0;
    for (size_t i = 0; i <= nrows; ++i) {
        if (i < nrows) {
            const int k0 = off[i], k1 = off[i + 1];
            if (k0 == k1) continue;
            const double xi0 = x[3 * i], xi1 = x[3 * i + 1], xi2 = x[3 * i + 2];
            const double ai = rad[i];
            /* phase 1 (gather): which entries touch; appended to the block */
            for (int k = k0; k < k1; ++k) {
                const int j = nbj[k];
                double d[3];
                dem_pair_offset(w, x, nbs, xi0, xi1, xi2, (size_t)j, k, periodic, d);
                const double d0 = d[0], d1 = d[1], d2 = d[2];
                const double aj = rad[j], s = ai + aj;
                const double r2 = d0 * d0 + d1 * d1 + d2 * d2;
                const int touch = r2 < s * s;
                {   /* branch-free: a non-touching entry loses its history and is overwritten next */
                    double *h = nbh + 3 * (size_t)k;
                    const double keep = touch ? 1.0 : 0.0;
                    h[0] *= keep; h[1] *= keep; h[2] *= keep;
                }
                /* only what the touch test needs and the indices: the other
                   per-contact values are gathered for the touching ones below */
                Bd0[nc] = d0; Bd1[nc] = d1; Bd2[nc] = d2; Bs[nc] = s;
                Bj[nc] = j; Bk[nc] = k; Bi[nc] = (int)i;
                nc += touch;
            }
            if (nc < DEM_PHASED_BLOCK) continue;  /* rows are never split: buffer >= block + longest row */
        }
        if (nc == 0) continue;
        nct += (size_t)nc;
        /* phase 1b (gather, touching contacts only): masses, radii, inertia, pair constants */
        for (int a = 0; a < nc; ++a) {
            const int j = Bj[a], ii = Bi[a];
            const double ai = rad[ii], mi = mass[ii];
            Bmj[a] = mass[j]; Baj[a] = rad[j];
            Bai[a] = ai; Bmi[a] = mi; BIi[a] = 0.4 * mi * ai * ai;
            if (!uniform) consts(B, L, a, pt + (size_t)mat[ii] * nm + mat[j]);
        }
        /* phase 2 (vector): geometry, normal force */
        geometry(w, B, L, nc, uniform, pred);
        {   /* the largest overlap ratio: the serial update only in a block that
               raises it (a test against the block's first value vectorises) */
            int up = 0;
            const double m0 = movr;
            for (int a = 0; a < nc; ++a) up |= Bdelta[a] > m0 * Bs[a];
            if (up)
                for (int a = 0; a < nc; ++a) {
                    const double ov = Bdelta[a];
                    if (ov > movr * Bs[a]) movr = ov / Bs[a];
                }
        }
        /* phase 3 (gather) */
        dem_phased_kinematics(w, B, nc, uniform != 2);
        /* phases 4- (vector, then scatter) */
        forces(w, B, L, nc, uniform, pred, rec);
        nc = 0;
    }
    *maxov = movr;
    *ncont = nct;
}

/* A law's pair_forces from its phased loop LOOP(w, periodic, uniform, pred,
 * rec, movr, nct): the specialisation chosen once per force evaluation.
 * uniform: 0 several materials (per-contact constants), 1 one material,
 * 2 one material without rolling friction (mu_r = 0: the loop skips the
 * relative spin and the rolling torque, which are zero).
 * Recording uses the general (per-contact constants) loop, whose arithmetic
 * is that of the uniform one with the same values, so the bits agree. */
#define DEM_PHASED_DISPATCH(LOOP, w, per, movr, nct) do {                                                   \
    const int u_ = (w)->nmat == 1 ? ((w)->pair[0].mu_r > 0.0 ? 1 : 2) : 0;                                  \
    const int pred_ = (w)->cfg.damping_predicted != 0;                                                      \
    if ((w)->crec_now) {                                                                                    \
        if (!pred_) { if (per) LOOP(w, 1, 0, 0, 1, movr, nct); else LOOP(w, 0, 0, 0, 1, movr, nct); }       \
        else        { if (per) LOOP(w, 1, 0, 1, 1, movr, nct); else LOOP(w, 0, 0, 1, 1, movr, nct); }       \
    } else if (!pred_) {                                                                                    \
        if (u_ == 2) { if (per) LOOP(w, 1, 2, 0, 0, movr, nct); else LOOP(w, 0, 2, 0, 0, movr, nct); }      \
        else if (u_) { if (per) LOOP(w, 1, 1, 0, 0, movr, nct); else LOOP(w, 0, 1, 0, 0, movr, nct); }      \
        else    { if (per) LOOP(w, 1, 0, 0, 0, movr, nct); else LOOP(w, 0, 0, 0, 0, movr, nct); }           \
    } else {                                                                                                \
        if (u_ == 2) { if (per) LOOP(w, 1, 2, 1, 0, movr, nct); else LOOP(w, 0, 2, 1, 0, movr, nct); }      \
        else if (u_) { if (per) LOOP(w, 1, 1, 1, 0, movr, nct); else LOOP(w, 0, 1, 1, 0, movr, nct); }      \
        else    { if (per) LOOP(w, 1, 0, 1, 0, movr, nct); else LOOP(w, 0, 0, 1, 0, movr, nct); }           \
    } } while (0)

#endif
