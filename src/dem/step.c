/*---------------------------------------------------------------------------*\
  demFoam DEM core - time integration.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

  Velocity Verlet (kick dt/2, drift dt, forces, kick dt/2) for translation
  and rotation of spheres (I = 2/5 m a^2).  The contact force/torque of the
  last evaluation is stored; gravity, force_ext/torque_ext and the drag are
  added at each kick, so the caller may change them between calls.
  Drag K (u - v) is integrated implicitly in each half kick h = dt/2:
      m (v' - v) / h = F + K (u - v')  =>  v' = (v + h (F/m + K u/m)) / (1 + h K/m)
  and drag_impulse += K (u - v') h, which is exactly the momentum the drag
  gave the particle (the fluid gets minus that).
  With an added (virtual) mass m_a > 0 (added_mass) the translational
  inertia is m + m_a while gravity stays m g:
      (m + m_a) (v' - v) / h = F + K (u - v') + m g
  i.e. the particle also feels -m_a dv/dt, integrated implicitly (its
  momentum over a step is -m_a (v_end - v_start), which the caller gives
  the fluid).  Rotation is unaffected (no added moment of inertia for a
  sphere).  m_a = 0 gives bit-identical results to the plain update.  The end kick of one step
  and the start kick of the next are done in the same pass.
  Split step (domain decomposition): dem_world_step_drift (start checks,
  start kick, drift, clock, outlets/inlets) and dem_world_step_forces (list
  check, forces, overlap check, end kick) use the same pieces as
  dem_world_step (step_begin, step_drift, step_force_eval, step_end_kick);
  the fused pair of kicks does the same IEEE operations as two single
  kicks, so n drift/forces pairs give the bits of dem_world_step(w, n)
  (tests/dem/test_decomp.c).  The drift's largest displacement is kept in
  the world (drift_d2max) for the force half; drift_pending guards the
  order of the calls.
\*---------------------------------------------------------------------------*/
#include "dem_private.h"
#include <math.h>
#include <string.h>

static dem_status check_state(dem_world *w, double *vmax)
{
    size_t np = w->n;
    double v2max = 0;
    for (size_t i = 0; i < np; ++i) {
        const double *x = w->x + 3 * i, *v = w->v + 3 * i, *om = w->w + 3 * i;
        double s = x[0] + x[1] + x[2] + v[0] + v[1] + v[2] + om[0] + om[1] + om[2];
        if (w->have_ext)
            s += w->fext[3 * i] + w->fext[3 * i + 1] + w->fext[3 * i + 2] + w->text[3 * i] +
                 w->text[3 * i + 1] + w->text[3 * i + 2] + w->K[i] + w->uf[3 * i] +
                 w->uf[3 * i + 1] + w->uf[3 * i + 2] + w->Ma[i];
        if (!isfinite(s)) {
            const char *what = "position";
            for (int k = 0; k < 3; ++k) {
                if (!isfinite(v[k])) what = "velocity";
                if (!isfinite(om[k])) what = "angular velocity";
            }
            for (int k = 0; k < 3; ++k) if (!isfinite(x[k])) what = "position";
            if (w->have_ext && !strcmp(what, "position") && isfinite(x[0] + x[1] + x[2]))
                what = "force_ext/torque_ext/drag_coeff/fluid_velocity/added_mass";
            return DEM_FAIL(w, DEM_ERR_NAN, "particle index %zu id %lld: non-finite %s (step %lld, t = %g)",
                            i, (long long)w->id[i], what, (long long)w->step, w->time);
        }
        if (w->have_ext && w->K[i] < 0)
            return DEM_FAIL(w, DEM_ERR_RANGE, "particle index %zu id %lld: drag_coeff = %g; allowed >= 0",
                            i, (long long)w->id[i], w->K[i]);
        if (w->have_ext && w->Ma[i] < 0)
            return DEM_FAIL(w, DEM_ERR_RANGE, "particle index %zu id %lld: added_mass = %g; allowed >= 0",
                            i, (long long)w->id[i], w->Ma[i]);
        double v2 = dem_dot(v, v);
        if (v2 > v2max) v2max = v2;
    }
    *vmax = sqrt(v2max);
    return DEM_OK;
}

static double max_wall_speed(const dem_world *w)
{
    double m = 0;
    for (int k = 0; k < w->nplanes; ++k) m = fmax(m, sqrt(dem_dot(w->planes[k].vel, w->planes[k].vel)));
    for (int k = 0; k < w->nmeshes; ++k) m = fmax(m, sqrt(dem_dot(w->meshes[k].vel, w->meshes[k].vel)));
    return m;
}

/* nk (1 or 2) successive half kicks of particle i; two kicks are the same
 * arithmetic as two single calls (bit-identical across call boundaries). */
static inline void kick_n(dem_world *w, size_t i, double h, const double *g, int nk)
{
    double *v = w->v + 3 * i, *om = w->w + 3 * i;
    const double *f = w->f + 3 * i, *t = w->t + 3 * i;
    const double m = w->mass[i], im = 1.0 / m;
    const double iI = 2.5 * im / (w->rad[i] * w->rad[i]);
    for (int rep = 0; rep < nk; ++rep) {
        if (!w->have_ext) {
            for (int k = 0; k < 3; ++k) {
                v[k] += h * (f[k] * im + g[k]);
                om[k] += h * t[k] * iI;
            }
            continue;
        }
        const double *fe = w->fext + 3 * i, *te = w->text + 3 * i, *u = w->uf + 3 * i;
        const double K = w->K[i];
        /* translational inverse inertia and gravity factor m/(m + m_a) */
        const double ma = w->Ma[i];
        const double imt = ma > 0 ? 1.0 / (m + ma) : im;
        const double gf = ma > 0 ? m * imt : 1.0;
        if (K > 0) {
            const double den = 1.0 / (1.0 + h * K * imt);
            double *J = w->J + 3 * i;
            for (int k = 0; k < 3; ++k) {
                double vn = (v[k] + h * ((f[k] + fe[k] + K * u[k]) * imt + g[k] * gf)) * den;
                J[k] += K * (u[k] - vn) * h;
                v[k] = vn;
            }
        } else {
            for (int k = 0; k < 3; ++k) v[k] += h * ((f[k] + fe[k]) * imt + g[k] * gf);
        }
        for (int k = 0; k < 3; ++k) om[k] += h * (t[k] + te[k]) * iI;
    }
}
static inline void kick1(dem_world *w, size_t i, double h, const double *g) { kick_n(w, i, h, g, 1); }

/* Kicks (nk = 1 or 2 half kicks), drift and the largest squared displacement
 * since the last list build, for the common case without coupling arrays:
 * the arithmetic of kick_n and of the drift in dem_world_step, in one loop
 * the compiler vectorises; multiversioned like the pair loop (laws/hertzMindlin.c), so
 * the same IEEE operations run in every version (bit-identical results). */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline double kick_drift_loop(dem_world *w, double h, double dt, const double *g, const int nk)
{
    const size_t n = w->n;
    double *restrict x = w->x, *restrict v = w->v, *restrict om = w->w;
    const double *restrict f = w->f, *restrict t = w->t, *restrict mass = w->mass, *restrict rad = w->rad;
    const float *restrict x0 = w->x0;
    const double g0 = g[0], g1 = g[1], g2 = g[2];
    double d2max = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const double im = 1.0 / mass[i];
        const double iI = 2.5 * im / (rad[i] * rad[i]);
        double v0 = v[3 * i], v1 = v[3 * i + 1], v2 = v[3 * i + 2];
        double w0 = om[3 * i], w1 = om[3 * i + 1], w2 = om[3 * i + 2];
        const double f0 = f[3 * i], f1 = f[3 * i + 1], f2 = f[3 * i + 2];
        const double t0 = t[3 * i], t1 = t[3 * i + 1], t2 = t[3 * i + 2];
        v0 += h * (f0 * im + g0); v1 += h * (f1 * im + g1); v2 += h * (f2 * im + g2);
        w0 += h * t0 * iI; w1 += h * t1 * iI; w2 += h * t2 * iI;
        if (nk == 2) {
            v0 += h * (f0 * im + g0); v1 += h * (f1 * im + g1); v2 += h * (f2 * im + g2);
            w0 += h * t0 * iI; w1 += h * t1 * iI; w2 += h * t2 * iI;
        }
        v[3 * i] = v0; v[3 * i + 1] = v1; v[3 * i + 2] = v2;
        om[3 * i] = w0; om[3 * i + 1] = w1; om[3 * i + 2] = w2;
        const double x0_ = x[3 * i] + dt * v0, x1_ = x[3 * i + 1] + dt * v1, x2_ = x[3 * i + 2] + dt * v2;
        x[3 * i] = x0_; x[3 * i + 1] = x1_; x[3 * i + 2] = x2_;
        const double e0 = x0_ - x0[3 * i], e1 = x1_ - x0[3 * i + 1], e2 = x2_ - x0[3 * i + 2];
        const double d2 = e0 * e0 + e1 * e1 + e2 * e2;
        d2max = d2 > d2max ? d2 : d2max;
    }
    return d2max;
}
DEM_MULTIVERSION
static double kick_drift_plain(dem_world *w, double h, double dt, const double *g, int nk)
{
    return nk == 2 ? kick_drift_loop(w, h, dt, g, 2) : kick_drift_loop(w, h, dt, g, 1);
}

/* The contact time the step check uses (HUGE_VAL without particles), after
 * the pair table update and the state check of dem_world_step. */
static dem_status step_contact_time(dem_world *w, double *tc, double *vimp)
{
    dem_status st = dem_pairs_update(w);
    if (st) return st;
    double vmax = 0;
    if ((st = check_state(w, &vmax))) return st;
    *vimp = 2.0 * vmax + max_wall_speed(w);
    *tc = HUGE_VAL;
    if (w->n) {
        int rayleigh = 1;
        if (w->cfg.impact_speed > 0) { *vimp = fmax(*vimp, w->cfg.impact_speed); rayleigh = 0; }
        dem_contact_time_internal(w, *vimp, rayleigh, 0, tc);
    }
    return DEM_OK;
}

dem_status dem_world_max_dt(dem_world *w, double *dt_max)
{
    if (!w) return DEM_ERR_ARG;
    if (!dt_max) return DEM_FAIL(w, DEM_ERR_ARG, "max_dt: dt_max must not be NULL");
    double tc, vimp;
    dem_status st = step_contact_time(w, &tc, &vimp);
    if (st) return st;
    *dt_max = w->n ? w->cfg.max_dt_fraction * tc : HUGE_VAL;
    return DEM_OK;
}

/* The start of dem_world_step and dem_world_step_drift: no half step
 * pending, step counter and time range for nsteps more steps, the time-step
 * check, a list build if invalid and the first force evaluation. */
static dem_status step_begin(dem_world *w, int64_t nsteps, const char *fn)
{
    if (w->drift_pending)
        return DEM_FAIL(w, DEM_ERR_STATE, "%s: step %lld is half done (dem_world_step_drift was called); "
                        "call dem_world_step_forces first", fn, (long long)w->step);
    if (nsteps > INT64_MAX - w->step)
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: nsteps = %lld after %lld steps; allowed at most %lld (step counter)",
                        fn, (long long)nsteps, (long long)w->step, (long long)(INT64_MAX - w->step));
    if (!isfinite(w->time + (double)nsteps * w->cfg.dt))
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: nsteps = %lld with dt = %g from t = %g; the time would not be "
                        "finite", fn, (long long)nsteps, w->cfg.dt, w->time);
    double tc, vimp;
    dem_status st = step_contact_time(w, &tc, &vimp);
    if (st) return st;
    if (w->n && w->cfg.dt > w->cfg.max_dt_fraction * tc)
        return DEM_FAIL(w, DEM_ERR_TIMESTEP, "dt = %g exceeds max_dt_fraction %g x smallest contact "
                        "time %g s (impact speed %g m/s) = %g s", w->cfg.dt, w->cfg.max_dt_fraction,
                        tc, vimp, w->cfg.max_dt_fraction * tc);
    if (!w->list_valid && (st = dem_list_build(w))) return st;
    if (!w->forces_valid) dem_forces(w, 0.0); /* first evaluation: no history increment */
    return DEM_OK;
}

/* nk half kicks and the drift of the owned particles, the clock advanced by
 * dt and the outlets/inlets run; *d2max: the largest squared displacement
 * since the last list build (of the particles owned at the drift). */
static dem_status step_drift(dem_world *w, int nk, double *d2max)
{
    const double dt = w->cfg.dt, h = 0.5 * dt;
    const double *g = w->cfg.gravity;
    double dm = 0;
    const size_t n = w->n;
    DEM_PROF_START(t0);
    if (!w->have_ext) dm = kick_drift_plain(w, h, dt, g, nk);
    else for (size_t i = 0; i < n; ++i) {
        kick_n(w, i, h, g, nk);
        double *x = w->x + 3 * i;
        const double *v = w->v + 3 * i;
        const float *x0 = w->x0 + 3 * i;
        x[0] += dt * v[0]; x[1] += dt * v[1]; x[2] += dt * v[2];
        double e0 = x[0] - x0[0], e1 = x[1] - x0[1], e2 = x[2] - x0[2];
        double d2 = e0 * e0 + e1 * e1 + e2 * e2;
        if (d2 > dm) dm = d2;
    }
    *d2max = dm;
    DEM_PROF_ADD(w, DEM_PROF_INTEGRATE, t0);
    w->step++;
    w->time += dt;
    dem_status st;
    if (w->ninlets > 0 || w->noutlets > 0) {
        if ((st = dem_outlets_run(w))) return st;
        if ((st = dem_inlets_run(w))) return st;
    }
    return DEM_OK;
}

/* 1 if the list is invalid or if the displacement since the build (d2max
 * of the drift; walls moving at speed vw) may exceed the skin: the
 * criterion of step_force_eval (and of dem_world_list_stale). */
static int list_needs_build(const dem_world *w, double d2max, double vw)
{
    double dmax = sqrt(d2max), dwall = vw * (w->time - w->t_build);
    return !w->list_valid || 2.0 * dmax > w->skin || dmax + dwall > w->skin;
}

/* The force half without its end kick: list rebuild if list_needs_build,
 * the force evaluation and the overlap check. */
static dem_status step_force_eval(dem_world *w, double d2max, double vw)
{
    dem_status st;
    if (list_needs_build(w, d2max, vw)) {
        DEM_PROF_START(t0);
        st = dem_list_build(w);
        DEM_PROF_ADD(w, DEM_PROF_NEIGHBOUR, t0);
        if (st) return st;
    }
    dem_forces(w, w->cfg.dt);
    if (w->max_overlap > w->cfg.max_overlap_ratio)
        return DEM_FAIL(w, DEM_ERR_OVERLAP, "overlap / diameter = %g exceeds max_overlap_ratio %g "
                        "at step %lld (t = %g)", w->max_overlap, w->cfg.max_overlap_ratio,
                        (long long)w->step, w->time);
    return DEM_OK;
}

/* The end half kick of the owned particles. */
static void step_end_kick(dem_world *w)
{
    const double h = 0.5 * w->cfg.dt;
    DEM_PROF_START(t0);
    for (size_t i = 0; i < w->n; ++i) kick1(w, i, h, w->cfg.gravity);
    DEM_PROF_ADD(w, DEM_PROF_INTEGRATE, t0);
}

dem_status dem_world_step(dem_world *w, int64_t nsteps)
{
    if (!w) return DEM_ERR_ARG;
    if (nsteps < 0) return DEM_FAIL(w, DEM_ERR_RANGE, "step: nsteps = %lld; allowed >= 0", (long long)nsteps);
    if (w->drift_pending || nsteps > 0) {
        dem_status st = step_begin(w, nsteps, "step");
        if (st) return st;
    }
    if (nsteps == 0) return DEM_OK;
    const double vw = max_wall_speed(w);
    dem_status result = DEM_OK;
    for (int64_t s = 0; s < nsteps && !result; ++s) {
        /* the end kick of step s-1 and the start kick of step s in one pass */
        double d2max;
        if ((result = step_drift(w, s > 0 ? 2 : 1, &d2max))) break;
        result = step_force_eval(w, d2max, vw);
    }
    step_end_kick(w);
    return result;
}

dem_status dem_world_step_drift(dem_world *w)
{
    if (!w) return DEM_ERR_ARG;
    dem_status st = step_begin(w, 1, "step_drift");
    if (st) return st;
    if ((st = step_drift(w, 1, &w->drift_d2max))) {
        step_end_kick(w); /* as dem_world_step(w, 1) on this error */
        return st;
    }
    w->drift_pending = 1;
    return DEM_OK;
}

/* The drift of a later step of a run of split steps: the start checks of
 * step_begin (state, time step, contact time: an O(n) pass) were done by the
 * run's first dem_world_step_drift, as dem_world_step(w, n) does them once
 * for its n steps; the full start when the list or the forces are not valid
 * (then it is not the continuation of a completed step). */
dem_status dem_world_step_drift_next(dem_world *w)
{
    if (!w) return DEM_ERR_ARG;
    if (w->drift_pending || !w->list_valid || !w->forces_valid || w->step == INT64_MAX)
        return dem_world_step_drift(w);
    dem_status st = step_drift(w, 1, &w->drift_d2max);
    if (st) {
        step_end_kick(w); /* as dem_world_step_drift on this error */
        return st;
    }
    w->drift_pending = 1;
    return DEM_OK;
}

dem_status dem_world_step_forces(dem_world *w)
{
    if (!w) return DEM_ERR_ARG;
    if (!w->drift_pending)
        return DEM_FAIL(w, DEM_ERR_STATE, "step_forces: no half step pending at step %lld; call "
                        "dem_world_step_drift first (one step = step_drift, then step_forces)", (long long)w->step);
    w->drift_pending = 0;
    dem_status st = step_force_eval(w, w->drift_d2max, max_wall_speed(w));
    step_end_kick(w);
    return st;
}

int dem_world_list_stale(const dem_world *w)
{
    if (!w) return 0;
    if (!w->drift_pending) return !w->list_valid;
    return list_needs_build(w, w->drift_d2max, max_wall_speed(w));
}

double dem_world_ghost_displacement(const dem_world *w)
{
    if (!w || !w->list_valid) return 0.0;
    double d2max = 0.0;
    for (size_t i = w->n; i < w->n + w->ng && i < w->nrows; ++i) {
        const double *x = w->x + 3 * i;
        const float *x0 = w->x0 + 3 * i;
        const double e0 = x[0] - x0[0], e1 = x[1] - x0[1], e2 = x[2] - x0[2];
        const double d2 = e0 * e0 + e1 * e1 + e2 * e2;
        d2max = d2 > d2max ? d2 : d2max;
    }
    return sqrt(d2max);
}

int dem_world_list_invalid(const dem_world *w)
{
    return w ? !w->list_valid : 0;
}

double dem_world_drift_displacement(const dem_world *w)
{
    if (!w || !w->drift_pending) return 0.0;
    return sqrt(w->drift_d2max);
}

dem_status dem_world_invalidate_list(dem_world *w)
{
    if (!w) return DEM_ERR_ARG;
    /* the rebuild carries the history of the current list through
       list_index (and the pending store), as for any other invalidation */
    w->list_valid = 0;
    return DEM_OK;
}
