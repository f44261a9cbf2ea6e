/*---------------------------------------------------------------------------*\
  demFoam DEM core - contact forces.

  Convention (written once): for a pair (i, j) n = (x_i - x_j)/|x_i - x_j|
  points from j to i, delta = a_i + a_j - |x_i - x_j|, the contact-point
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
  - Linear / Hertzian spring-dashpot [S] 17-26 (sd_force).
  Tangential history h: rotated into the current tangent plane (magnitude
  kept), then h += v_t dt.
\*---------------------------------------------------------------------------*/
#include "dem_private.h"
#include <math.h>
#include <string.h>

static inline void rotate_history(double *h, const double n[3])
{
    double hn = h[0] * n[0] + h[1] * n[1] + h[2] * n[2];
    if (hn != 0.0) {
        double h2 = h[0] * h[0] + h[1] * h[1] + h[2] * h[2];
        h[0] -= hn * n[0]; h[1] -= hn * n[1]; h[2] -= hn * n[2];
        double h2n = h[0] * h[0] + h[1] * h[1] + h[2] * h[2];
        if (h2n > 0.0) {
            double s = sqrt(h2 / h2n);
            h[0] *= s; h[1] *= s; h[2] *= s;
        }
    }
}

/* Hertz-Mindlin [Z] Table 2.  Returns the force on i in F, the elastic
 * normal force |f_cn| in *fel, tangential force in ft. */
static inline void hm_force(const dem_pair *q, double dt, const double n[3], double delta,
                            const double vc[3], double meff, double rstar, double *h,
                            double F[3], double ft[3], double *fel)
{
    double vn = vc[0] * n[0] + vc[1] * n[1] + vc[2] * n[2];
    double vt[3] = {vc[0] - vn * n[0], vc[1] - vn * n[1], vc[2] - vn * n[2]};
    double sq = sqrt(rstar * delta);
    double fcn = (4.0 / 3.0) * q->estar * sq * delta;              /* (4/3) E* sqrt(R*) delta^(3/2) */
    double fn = fcn - q->cn * sqrt(8.0 * meff * q->estar * sq) * vn; /* + c_n (8 m E* sqrt(R* delta))^(1/2) (-v_n) */
    ft[0] = ft[1] = ft[2] = 0.0;
    if (q->mu > 0.0) {
        rotate_history(h, n);
        h[0] += vt[0] * dt; h[1] += vt[1] * dt; h[2] += vt[2] * dt;
        double dtmax = q->mu * q->mindlin * delta;                  /* delta_t,max */
        double hm = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
        if (hm >= dtmax) {                                          /* Coulomb sliding */
            double s = dtmax / hm;
            h[0] *= s; h[1] *= s; h[2] *= s;
            double c = -q->mu * fcn / dtmax;                        /* -mu |f_cn| h/|h| */
            ft[0] = c * h[0]; ft[1] = c * h[1]; ft[2] = c * h[2];
        } else {
            double r = 1.0 - hm / dtmax, sr = sqrt(r);
            if (hm > 0.0) {
                double c = -q->mu * fcn * (1.0 - r * sr) / hm;
                ft[0] = c * h[0]; ft[1] = c * h[1]; ft[2] = c * h[2];
            }
            double cd = -q->ct * sqrt(6.0 * q->mu * meff * fcn * sr / dtmax);
            ft[0] += cd * vt[0]; ft[1] += cd * vt[1]; ft[2] += cd * vt[2];
        }
    } else {
        h[0] = h[1] = h[2] = 0.0;
    }
    F[0] = fn * n[0] + ft[0]; F[1] = fn * n[1] + ft[1]; F[2] = fn * n[2] + ft[2];
    *fel = fcn;
}

/* Spring-dashpot [S] 17-26; fscale = 1 (linear) or sqrt(delta/d) (Hertzian). */
static inline void sd_force(const dem_pair *q, double dt, const double n[3], double delta,
                            double fscale, const double vc[3], double meff, double *h,
                            double F[3], double ft[3], double *fel)
{
    double vn = vc[0] * n[0] + vc[1] * n[1] + vc[2] * n[2];
    double vt[3] = {vc[0] - vn * n[0], vc[1] - vn * n[1], vc[2] - vn * n[2]};
    double eta = q->eta_fixed >= 0.0 ? q->eta_fixed : q->beta * sqrt(q->kn * meff); /* gamma_n m_eff */
    double etat = 0.5 * eta;  /* tangential damping: half the normal one (LAMMPS gran/hooke/history default) */
    double fel_ = fscale * q->kn * delta;
    double fn = fel_ - fscale * eta * vn;
    ft[0] = ft[1] = ft[2] = 0.0;
    if (q->mu > 0.0) {
        rotate_history(h, n);
        h[0] += vt[0] * dt; h[1] += vt[1] * dt; h[2] += vt[2] * dt;
        for (int k = 0; k < 3; ++k) ft[k] = fscale * (-q->kt * h[k] - etat * vt[k]);
        double ftm = sqrt(ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2]);
        double lim = q->mu * fabs(fn);
        if (ftm > lim) {
            double s = lim / ftm;
            for (int k = 0; k < 3; ++k) {
                ft[k] *= s;
                /* keep the spring consistent with the truncated force */
                h[k] = fscale > 0 ? -(ft[k] / fscale + etat * vt[k]) / q->kt : 0.0;
            }
        }
    } else {
        h[0] = h[1] = h[2] = 0.0;
    }
    F[0] = fn * n[0] + ft[0]; F[1] = fn * n[1] + ft[1]; F[2] = fn * n[2] + ft[2];
    *fel = fel_;
}

/* Rolling friction torque on i (j gets the opposite): -mu_r |f_cn| w/|w|,
 * w = w_i - w_j, magnitude limited to |w| / (dt (1/I_i + 1/I_j)). */
static inline void rolling(double mu_r, double fel, const double *wi, const double *wj,
                           double inv_I_sum_dt, double M[3])
{
    double wr[3] = {wi[0] - (wj ? wj[0] : 0), wi[1] - (wj ? wj[1] : 0), wi[2] - (wj ? wj[2] : 0)};
    double wm = sqrt(wr[0] * wr[0] + wr[1] * wr[1] + wr[2] * wr[2]);
    if (wm <= 0.0) { M[0] = M[1] = M[2] = 0.0; return; }
    double m = mu_r * fel, mmax = wm / inv_I_sum_dt;
    if (m > mmax) m = mmax;
    double c = -m / wm;
    M[0] = c * wr[0]; M[1] = c * wr[1]; M[2] = c * wr[2];
}

/* The pair loop, specialised by law and periodicity at compile time. */
#define LAW_HM 0
#define LAW_LSD 1
#define LAW_HSD 2
static inline void pair_loop(dem_world *w, const int law, const int periodic,
                             double *maxov, size_t *ncont)
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
            const double r = sqrt(r2), ir = 1.0 / r;
            const double n[3] = {d0 * ir, d1 * ir, d2 * ir};
            const double delta = s - r;
            nct++;
            if (delta > movr * s) movr = delta / s;
            const double mj = mass[j];
            const double meff = mi * mj / (mi + mj);
            const double *wj = om + 3 * j, *vj = v + 3 * j;
            /* (a_i w_i + a_j w_j) x n */
            const double W0 = ai * wi[0] + aj * wj[0], W1 = ai * wi[1] + aj * wj[1],
                         W2 = ai * wi[2] + aj * wj[2];
            const double vc[3] = {vi[0] - vj[0] - (W1 * n[2] - W2 * n[1]),
                                  vi[1] - vj[1] - (W2 * n[0] - W0 * n[2]),
                                  vi[2] - vj[2] - (W0 * n[1] - W1 * n[0])};
            const dem_pair *q = prow + mat[j];
            double F[3], ft[3], fel;
            if (law == LAW_HM)
                hm_force(q, dt, n, delta, vc, meff, ai * aj / s, h, F, ft, &fel);
            else
                sd_force(q, dt, n, delta, law == LAW_HSD ? sqrt(delta / s) : 1.0, vc, meff, h, F, ft, &fel);
            fi0 += F[0]; fi1 += F[1]; fi2 += F[2];
            f[3 * j] -= F[0]; f[3 * j + 1] -= F[1]; f[3 * j + 2] -= F[2];
            /* torques: T_i = -a_i n x f_t, T_j = -a_j n x f_t */
            const double c0 = n[1] * ft[2] - n[2] * ft[1], c1 = n[2] * ft[0] - n[0] * ft[2],
                         c2 = n[0] * ft[1] - n[1] * ft[0];
            ti0 -= ai * c0; ti1 -= ai * c1; ti2 -= ai * c2;
            t[3 * j] -= aj * c0; t[3 * j + 1] -= aj * c1; t[3 * j + 2] -= aj * c2;
            if (q->mu_r > 0.0) {
                double M[3];
                double iIsum = 2.5 / (mi * ai * ai) + 2.5 / (mj * aj * aj);
                rolling(q->mu_r, fel, wi, wj, iIsum * dt, M);
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

/* One wall contact of particle i with unit normal n (wall -> centre),
 * overlap delta, wall velocity vw. */
static inline void wall_contact(dem_world *w, int law, size_t i, const double n[3], double delta,
                                const double vw[3], int wallmat, double *h)
{
    const double ai = w->rad[i], mi = w->mass[i];
    const double *vi = w->v + 3 * i, *wi = w->w + 3 * i;
    const double W[3] = {ai * wi[0], ai * wi[1], ai * wi[2]};
    double cr[3];
    dem_cross(W, n, cr);
    const double vc[3] = {vi[0] - vw[0] - cr[0], vi[1] - vw[1] - cr[1], vi[2] - vw[2] - cr[2]};
    const dem_pair *q = &w->pair[(size_t)w->mat_of[i] * w->nmat + wallmat];
    double F[3], ft[3], fel;
    if (law == LAW_HM)
        hm_force(q, w->hdt, n, delta, vc, mi, ai, h, F, ft, &fel);
    else
        sd_force(q, w->hdt, n, delta, law == LAW_HSD ? sqrt(delta / (2.0 * ai)) : 1.0, vc, mi, h,
                 F, ft, &fel);
    double c[3];
    dem_cross(n, ft, c);
    for (int k = 0; k < 3; ++k) {
        w->f[3 * i + k] += F[k];
        w->t[3 * i + k] -= ai * c[k];
    }
    if (q->mu_r > 0.0) {
        double M[3];
        rolling(q->mu_r, fel, wi, NULL, 2.5 / (mi * ai * ai) * w->cfg.dt, M);
        for (int k = 0; k < 3; ++k) w->t[3 * i + k] += M[k];
    }
    w->wall_contacts++;
    if (delta > w->max_overlap * 2.0 * ai) w->max_overlap = delta / (2.0 * ai);
}

typedef struct { int k; int feature; int nv; int fv[3]; double d2, cp[3]; int acc; } mesh_cand;

static void wall_loop(dem_world *w, int law)
{
    const int *off = w->wc_off;
    for (size_t i = 0; i < w->n; ++i) {
        int k0 = off[i], k1 = off[i + 1];
        if (k0 == k1) continue;
        const double *xi = w->x + 3 * i;
        const double ai = w->rad[i];
        mesh_cand mc[64];
        int nmc = 0;
        for (int k = k0; k < k1; ++k) {
            int wall = w->wc_wall[k];
            double *h = w->wc_h + 3 * (size_t)k;
            if (w->wc_tri[k] < 0) {
                const dem_plane *P = &w->planes[w->wall_index[wall]];
                double d = 0;
                for (int c = 0; c < 3; ++c)
                    d += (xi[c] - P->x0[c] - P->vel[c] * (w->time - P->t0)) * P->n[c];
                if (d >= ai || d <= -ai) { h[0] = h[1] = h[2] = 0.0; continue; }
                wall_contact(w, law, i, P->n, ai - d, P->vel, P->material, h);
            } else {
                const dem_mesh *m = &w->meshes[w->wall_index[wall]];
                int t = w->wc_tri[k];
                double Pv[3][3], cp[3];
                for (int v = 0; v < 3; ++v)
                    for (int c = 0; c < 3; ++c)
                        Pv[v][c] = m->v0[3 * (size_t)m->tri[3 * t + v] + c] + m->vel[c] * (w->time - m->t0);
                int feat = dem_closest_on_triangle(xi, Pv[0], Pv[1], Pv[2], cp);
                double d2 = 0;
                for (int c = 0; c < 3; ++c) d2 += (xi[c] - cp[c]) * (xi[c] - cp[c]);
                if (d2 >= ai * ai || nmc >= 64) { continue; }
                mesh_cand *z = &mc[nmc++];
                z->k = k; z->feature = feat; z->d2 = d2; z->acc = 0;
                memcpy(z->cp, cp, sizeof cp);
                const int *tv = m->tri + 3 * t;
                static const int fv_of[7][3] = {{0, 1, 2}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0},
                                                {0, 1, 0}, {1, 2, 0}, {2, 0, 0}};
                z->nv = feat == 0 ? 3 : (feat <= 3 ? 1 : 2);
                for (int c = 0; c < z->nv; ++c) z->fv[c] = tv[fv_of[feat][c]];
            }
        }
        /* mesh candidates that are not touching lose their history below */
        if (nmc) {
            /* accept in order of distance; an edge/vertex contact whose
               vertices all belong to an accepted triangle is the same contact */
            for (int a = 0; a < nmc; ++a) {
                int best = -1;
                for (int b = 0; b < nmc; ++b)
                    if (!mc[b].acc && (best < 0 || mc[b].d2 < mc[best].d2 ||
                                       (mc[b].d2 == mc[best].d2 && mc[b].feature < mc[best].feature)))
                        best = b;
                mesh_cand *z = &mc[best];
                z->acc = 1;
                if (z->feature != 0) {
                    int wz = w->wc_wall[z->k];
                    for (int b = 0; b < nmc; ++b) {
                        if (b == best || mc[b].acc != 2 || w->wc_wall[mc[b].k] != wz) continue;
                        const dem_mesh *m = &w->meshes[w->wall_index[wz]];
                        const int *tv = m->tri + 3 * w->wc_tri[mc[b].k];
                        int all = 1;
                        for (int c = 0; c < z->nv && all; ++c)
                            all = z->fv[c] == tv[0] || z->fv[c] == tv[1] || z->fv[c] == tv[2];
                        if (all) { z->acc = 3; break; } /* rejected */
                    }
                }
                if (z->acc == 1) z->acc = 2; /* accepted */
            }
            /* history hand-over: a new accepted contact takes the history of a
               rejected/ended candidate of the same mesh */
            for (int a = 0; a < nmc; ++a) {
                if (mc[a].acc != 2) continue;
                double *h = w->wc_h + 3 * (size_t)mc[a].k;
                if (h[0] != 0 || h[1] != 0 || h[2] != 0) continue;
                int wz = w->wc_wall[mc[a].k];
                for (int k = k0; k < k1; ++k) {
                    if (w->wc_tri[k] < 0 || w->wc_wall[k] != wz || k == mc[a].k) continue;
                    int isacc = 0;
                    for (int b = 0; b < nmc; ++b) if (mc[b].k == k && mc[b].acc == 2) isacc = 1;
                    if (isacc) continue;
                    double *h2 = w->wc_h + 3 * (size_t)k;
                    if (h2[0] != 0 || h2[1] != 0 || h2[2] != 0) {
                        memcpy(h, h2, 3 * sizeof(double));
                        h2[0] = h2[1] = h2[2] = 0.0;
                        break;
                    }
                }
            }
        }
        for (int k = k0; k < k1; ++k) {
            if (w->wc_tri[k] < 0) continue;
            int a = -1;
            for (int b = 0; b < nmc; ++b) if (mc[b].k == k) { a = b; break; }
            double *h = w->wc_h + 3 * (size_t)k;
            if (a < 0 || mc[a].acc != 2) { h[0] = h[1] = h[2] = 0.0; continue; }
            int wall = w->wc_wall[k];
            const dem_mesh *m = &w->meshes[w->wall_index[wall]];
            double d = sqrt(mc[a].d2), n[3];
            if (d > 0) for (int c = 0; c < 3; ++c) n[c] = (xi[c] - mc[a].cp[c]) / d;
            else {
                const double *tn = m->nrm + 3 * w->wc_tri[k];
                for (int c = 0; c < 3; ++c) n[c] = tn[c];
            }
            wall_contact(w, law, i, n, ai - d, m->vel, m->material, h);
        }
    }
}

void dem_forces(dem_world *w, double hist_dt)
{
    w->hdt = hist_dt;
    size_t np = w->n + w->ng;
    memset(w->f, 0, 3 * np * sizeof(double));
    memset(w->t, 0, 3 * np * sizeof(double));
    double movr = 0.0;
    size_t nct = 0;
    int per = w->cfg.periodic[0] || w->cfg.periodic[1] || w->cfg.periodic[2];
    switch (w->cfg.contact_law) {
    case DEM_CONTACT_HERTZ_MINDLIN:
        if (per) pair_loop(w, LAW_HM, 1, &movr, &nct); else pair_loop(w, LAW_HM, 0, &movr, &nct);
        break;
    case DEM_CONTACT_LINEAR_SPRING_DASHPOT:
        if (per) pair_loop(w, LAW_LSD, 1, &movr, &nct); else pair_loop(w, LAW_LSD, 0, &movr, &nct);
        break;
    default:
        if (per) pair_loop(w, LAW_HSD, 1, &movr, &nct); else pair_loop(w, LAW_HSD, 0, &movr, &nct);
        break;
    }
    w->pair_contacts = nct;
    w->max_overlap = movr;
    w->wall_contacts = 0;
    if (w->nwalls) {
        int law = w->cfg.contact_law == DEM_CONTACT_HERTZ_MINDLIN ? LAW_HM
                : (w->cfg.contact_law == DEM_CONTACT_LINEAR_SPRING_DASHPOT ? LAW_LSD : LAW_HSD);
        wall_loop(w, law);
    }
    w->forces_valid = 1;
}
