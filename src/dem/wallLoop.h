/*---------------------------------------------------------------------------*\
  demFoam DEM core - the wall loop (plane and triangle-mesh contacts of every
  particle), written once and inlined into each law with the law's
  one-contact kernel (DEM_WALL_FORCES), so that a wall contact makes no
  indirect call.  Which triangle contacts count is decided in contact.c
  (dem_wall_mesh_contacts), the same for every law.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#ifndef DEM_WALL_LOOP_H
#define DEM_WALL_LOOP_H
#include "contactKernel.h"

/* most triangle candidates of one particle considered (more are ignored) */
#define DEM_WALL_MESH_MAX 64

/* An accepted triangle contact: list entry k, unit normal (wall -> centre), overlap. */
typedef struct { int k; double n[3], delta; } dem_mesh_contact;

/* The accepted triangle contacts of particle i among its wall-list entries
 * k0..k1-1, in entry order; the histories of the other triangle entries are
 * cleared or handed over (contact.c). */
int dem_wall_mesh_contacts(dem_world *w, size_t i, int k0, int k1, dem_mesh_contact out[DEM_WALL_MESH_MAX]);

/* The contact-point velocity of particle i against a wall moving at vw,
 * unit normal n (wall -> centre): v_i - v_w - (a_i w_i) x n. */
static DEM_ALWAYS_INLINE void dem_wall_contact_velocity(const dem_world *w, size_t i, const double n[3],
                                                        const double vw[3], double vc[3])
{
    const double ai = w->rad[i];
    const double *vi = w->v + 3 * i, *wi = w->w + 3 * i;
    const double W[3] = {ai * wi[0], ai * wi[1], ai * wi[2]};
    double cr[3];
    dem_cross(W, n, cr);
    vc[0] = vi[0] - vw[0] - cr[0]; vc[1] = vi[1] - vw[1] - cr[1]; vc[2] = vi[2] - vw[2] - cr[2];
}

/* What a wall contact of particle i adds, from the kernel's f_n, f_t and
 * f_cn (F = f_n n + f_t, as every kernel computes it: law.h): the contact
 * record, force and torque on i, rolling friction, the largest overlap
 * over 2 a_i in *movr. */
static DEM_ALWAYS_INLINE void dem_wall_contact_add(dem_world *w, size_t i, int wall, const dem_pair *q,
                                                   const double n[3], double delta, double fn, const double ft[3],
                                                   double fel, double *movr)
{
    const double ai = w->rad[i], mi = w->mass[i];
    if (w->crec_now) dem_record_contact(w, i, wall, 1, 0, delta, n, fn, ft);
    double c[3];
    dem_cross(n, ft, c);
    double *fi = w->f + 3 * i, *ti = w->t + 3 * i;
    for (int k = 0; k < 3; ++k) {
        fi[k] += fn * n[k] + ft[k];
        ti[k] -= ai * c[k];
    }
    if (q->mu_r > 0.0) {
        double M[3];
        dem_rolling(q->mu_r, fel, w->w + 3 * i, NULL, 0.4 * mi * ai * ai, 0.0, w->cfg.dt, M);
        for (int k = 0; k < 3; ++k) ti[k] += M[k];
    }
    if (delta > *movr * 2.0 * ai) *movr = delta / (2.0 * ai);
}

/* One wall contact of particle i through the one-contact kernel: unit
 * normal n (wall -> centre), overlap delta, wall velocity vw, the wall's material. */
static DEM_ALWAYS_INLINE void dem_wall_contact(dem_world *w, dem_contact_fn one, size_t i, int wall,
                                               const double n[3], double delta, const double vw[3], int wallmat,
                                               double *h, double *movr)
{
    const double ai = w->rad[i];
    double vc[3];
    dem_wall_contact_velocity(w, i, n, vw, vc);
    const dem_pair *q = &w->pair[(size_t)w->mat_of[i] * w->nmat + wallmat];
    double F[3], ft[3], fel, fn;
    one(q, w->hdt, n, delta, 2.0 * ai, vc, w->mass[i], ai, h, F, ft, &fel, &fn);
    dem_wall_contact_add(w, i, wall, q, n, delta, fn, ft, fel, movr);
}

/* Signed distance of centre xi from plane P (positive on its normal's side). */
static inline double dem_plane_distance(const dem_world *w, const dem_plane *P, const double *xi)
{
    double d = 0;
    for (int c = 0; c < 3; ++c) d += (xi[c] - P->x0[c] - P->vel[c] * (w->time - P->t0)) * P->n[c];
    return d;
}

/* Particle i's accepted triangle contacts (wall-list entries k0..k1-1)
 * through the one-contact kernel; returns their number. */
static DEM_ALWAYS_INLINE int dem_wall_mesh_loop(dem_world *w, dem_contact_fn one, size_t i, int k0, int k1,
                                                double *movr)
{
    dem_mesh_contact mc[DEM_WALL_MESH_MAX];
    const int nmc = dem_wall_mesh_contacts(w, i, k0, k1, mc);
    for (int a = 0; a < nmc; ++a) {
        const int wall = w->wc_wall[mc[a].k];
        const dem_mesh *m = &w->meshes[w->wall_index[wall]];
        dem_wall_contact(w, one, i, wall, mc[a].n, mc[a].delta, m->vel, m->material,
                         w->wc_h + 3 * (size_t)mc[a].k, movr);
    }
    return nmc;
}

/*--- plane contacts in blocks (vectorised laws) ----------------------------*/
/* A law whose one-contact kernel has a branch-free twin over arrays (its
 * wall block kernel) gets its plane contacts collected into blocks: the
 * gather (plane distance, contact-point velocity) and the scatter (torque,
 * rolling, record) stay scalar and in the order of the one-contact loop, the
 * kernel's square roots and divisions run in a loop the compiler vectorises.
 * The block kernel must do the one-contact kernel's IEEE operations, so that
 * results are bit-identical to the one-contact loop's. */
#define DEM_WALL_BLOCK DEM_PHASED_BLOCK
typedef struct {
    /* in: unit normal, overlap, contact-point velocity, m*, R*, the pair */
    double n0[DEM_WALL_BLOCK], n1[DEM_WALL_BLOCK], n2[DEM_WALL_BLOCK], delta[DEM_WALL_BLOCK];
    double vc0[DEM_WALL_BLOCK], vc1[DEM_WALL_BLOCK], vc2[DEM_WALL_BLOCK], meff[DEM_WALL_BLOCK],
        rstar[DEM_WALL_BLOCK];
    const dem_pair *q[DEM_WALL_BLOCK];
    /* in and out: tangential history */
    double h0[DEM_WALL_BLOCK], h1[DEM_WALL_BLOCK], h2[DEM_WALL_BLOCK];
    /* out: as the one-contact kernel's ft, fel, fn (F = fn n + ft follows) */
    double ft0[DEM_WALL_BLOCK], ft1[DEM_WALL_BLOCK], ft2[DEM_WALL_BLOCK], fel[DEM_WALL_BLOCK],
        fn[DEM_WALL_BLOCK];
    /* the skeleton's: particle, wall-list entry, wall */
    int i[DEM_WALL_BLOCK], k[DEM_WALL_BLOCK], wall[DEM_WALL_BLOCK];
} dem_wall_block;
typedef void (*dem_wall_block_fn)(const dem_world *w, dem_wall_block *b, int nc);

/* The start shared by the Hertz laws' block kernels, for slot a: the
 * normal force (into fel, fn), v_t (into vc), the history rotated and
 * advanced by v_t dt (into h); sqrt(R* delta) and sqrt(m* sqrt(R* delta))
 * returned in *sq and *dn (hp: half the step). */
static DEM_ALWAYS_INLINE void dem_hertz_block_start(dem_wall_block *b, int a, double k43, double cn8, double pred,
                                                    double dt, double hp, double *sq, double *dn)
{
    const double n0 = b->n0[a], n1 = b->n1[a], n2 = b->n2[a];
    const double vc0 = b->vc0[a], vc1 = b->vc1[a], vc2 = b->vc2[a];
    const double vn = vc0 * n0 + vc1 * n1 + vc2 * n2;
    const double vt0 = vc0 - vn * n0, vt1 = vc1 - vn * n1, vt2 = vc2 - vn * n2;
    double fcn, fn;
    dem_hertz_normal_select(k43, cn8, pred, b->rstar[a], b->delta[a], b->meff[a], vn, hp, sq, &fcn, dn, &fn);
    double hs[3] = {b->h0[a], b->h1[a], b->h2[a]};
    dem_history_step(n0, n1, n2, vt0, vt1, vt2, dt, hs);
    b->vc0[a] = vt0; b->vc1[a] = vt1; b->vc2[a] = vt2;
    b->h0[a] = hs[0]; b->h1[a] = hs[1]; b->h2[a] = hs[2];
    b->fel[a] = fcn; b->fn[a] = fn;
}

/* the block's kernel, then each contact's history and what it adds
 * (dem_wall_contact_add), in block order */
static DEM_ALWAYS_INLINE void dem_wall_block_flush(dem_world *w, dem_wall_block_fn kernel, dem_wall_block *b,
                                                   int nc, double *movr)
{
    if (!nc) return;
    kernel(w, b, nc);
    for (int a = 0; a < nc; ++a) {
        double *h = w->wc_h + 3 * (size_t)b->k[a];
        h[0] = b->h0[a]; h[1] = b->h1[a]; h[2] = b->h2[a];
        const double n[3] = {b->n0[a], b->n1[a], b->n2[a]}, ft[3] = {b->ft0[a], b->ft1[a], b->ft2[a]};
        dem_wall_contact_add(w, (size_t)b->i[a], b->wall[a], b->q[a], n, b->delta[a], b->fn[a], ft, b->fel[a],
                             movr);
    }
}

/* All wall contacts: per particle its planes in list order, then its
 * accepted triangles in list order (the order of the force sums).  With a
 * block kernel (not NULL) the plane contacts go through it in blocks, and
 * the block is flushed before a particle's triangles, so the order holds;
 * without, each contact calls the one-contact kernel. */
static DEM_ALWAYS_INLINE void dem_wall_loop(dem_world *w, dem_contact_fn one, dem_wall_block_fn kernel)
{
    const int *off = w->wc_off;
    double movr = w->max_overlap;
    size_t ncont = 0;
    dem_wall_block b;
    int nb = 0;
    for (size_t i = 0; i < w->n; ++i) {
        const int k0 = off[i], k1 = off[i + 1];
        if (k0 == k1) continue;
        const double *xi = w->x + 3 * i;
        const double ai = w->rad[i];
        int meshes = 0;
        for (int k = k0; k < k1; ++k) {
            if (w->wc_tri[k] >= 0) { meshes = 1; continue; }
            const int wall = w->wc_wall[k];
            double *h = w->wc_h + 3 * (size_t)k;
            const dem_plane *P = &w->planes[w->wall_index[wall]];
            const double d = dem_plane_distance(w, P, xi);
            if (d >= ai || d <= -ai) { h[0] = h[1] = h[2] = 0.0; continue; }
            ncont++;
            if (!kernel) {
                dem_wall_contact(w, one, i, wall, P->n, ai - d, P->vel, P->material, h, &movr);
                continue;
            }
            /* the inputs of dem_wall_contact's kernel call */
            double vc[3];
            dem_wall_contact_velocity(w, i, P->n, P->vel, vc);
            b.n0[nb] = P->n[0]; b.n1[nb] = P->n[1]; b.n2[nb] = P->n[2];
            b.delta[nb] = ai - d;
            b.vc0[nb] = vc[0]; b.vc1[nb] = vc[1]; b.vc2[nb] = vc[2];
            b.meff[nb] = w->mass[i]; b.rstar[nb] = ai;
            b.q[nb] = &w->pair[(size_t)w->mat_of[i] * w->nmat + P->material];
            b.h0[nb] = h[0]; b.h1[nb] = h[1]; b.h2[nb] = h[2];
            b.i[nb] = (int)i; b.k[nb] = k; b.wall[nb] = wall;
            if (++nb == DEM_WALL_BLOCK) { dem_wall_block_flush(w, kernel, &b, nb, &movr); nb = 0; }
        }
        if (!meshes) continue;
        if (kernel) dem_wall_block_flush(w, kernel, &b, nb, &movr);
        nb = 0;
        ncont += dem_wall_mesh_loop(w, one, i, k0, k1, &movr);
    }
    if (kernel) dem_wall_block_flush(w, kernel, &b, nb, &movr);
    w->max_overlap = movr;
    w->wall_contacts = ncont;
}

/* A law's wall loop `fn` with plane contacts through its block kernel
 * (compiled for AVX-512, AVX2 and generic x86-64 as the phased pair loops) */
#define DEM_WALL_FORCES_BLOCKED(fn, kernel, block) \
    DEM_MULTIVERSION __attribute__((noinline)) static void fn(dem_world *w) { dem_wall_loop(w, kernel, block); }

/* A law's wall loop `fn` with its kernel `kernel` inlined (its table's .wall_forces). */
#define DEM_WALL_FORCES(fn, kernel) \
    static void fn(dem_world *w) { dem_wall_loop(w, kernel, NULL); }

#endif
