/*---------------------------------------------------------------------------*\
  bench_dem - timed stepping of the settled bed with the demFoam DEM core
  (the "ours" half of bench/dem/run; LIGGGHTS runs in.bench on the same bed).
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

  Usage: bench_dem BEDFILE NSTEPS [LAW [ROLLING]]

  LAW: a contact-law name (dem_contact_law_name), default hertzMindlin.
  ROLLING: rolling (default; mu_r as below, the counterpart of LIGGGHTS'
  cdt) or norolling (mu_r = 0: the problem LAMMPS' in.lammps steps, whose
  granular pair style has no constant-torque rolling model).
  With a core built with -DDEM_PROFILE (bench/dem/profile) it also prints
  the seconds of each step phase (dem_world_phase_times) of the timed loop.

  BEDFILE is written by bed.py convert: magic "DEMBED01", int64 N, box lo[3],
  hi[3] (doubles), then per particle int64 id and 11 doubles
  x[3] v[3] omega[3] radius density (little endian).

  Problem (docs/performance.md, "The benchmark"): Hertz-Mindlin with history,
  E = 1e7 Pa, nu = 0.3, e = 0.9, mu_s = 0.4, rolling friction as LIGGGHTS'
  cdt with coefficient 0.01: LIGGGHTS applies 0.01 R* k_n delta_n, our law
  M_r = mu_r |F_n|, so mu_r = 0.01 R* = 0.01 x (R/2) = 5e-6 m for the
  particle pairs (equal spheres, R = 1 mm).  dt = 1e-6 s, skin 0.4 mm =
  0.2 d, gravity 9.81 m/s2, six plane walls of the same material.

  Timing: one untimed step first (it builds the neighbour list, as LIGGGHTS'
  setup does before its loop timer starts), then NSTEPS steps in one
  dem_world_step call timed with clock_gettime(CLOCK_MONOTONIC).

  Memory: dem_world_memory() (particle arrays; neighbour/wall lists with
  their contact history), and VmRSS/VmHWM of this process minus their values
  before the world was created.

  Output: key=value lines on stdout, read by bench/dem/run.
\*---------------------------------------------------------------------------*/
#define _POSIX_C_SOURCE 200809L
#include "dem.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define CHUNK 4096  /* particles read and added at a time (keeps the input buffer small) */

static long status_kb(const char *key)
{
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    long kb = -1;
    size_t n = strlen(key);
    if (!f) return -1;
    while (fgets(line, sizeof line, f))
        if (strncmp(line, key, n) == 0 && line[n] == ':') { kb = strtol(line + n + 1, NULL, 10); break; }
    fclose(f);
    return kb;
}

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double cpu_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static long n_log[3];
static void logger(dem_log_level level, const char *msg, void *user)
{
    (void)user;
    if (level >= 0 && level <= 2) n_log[level]++;
    if (level == DEM_LOG_WARNING) fprintf(stderr, "bench_dem: core warning: %s\n", msg);
}

static int check(dem_world *w, dem_status s, const char *what)
{
    if (s == DEM_OK) return 0;
    fprintf(stderr, "bench_dem: %s failed: %s (%s)\n", what, dem_status_string(s),
            w ? dem_world_last_error(w) : "");
    return 1;
}

int main(int argc, char **argv)
{
    if (argc < 3 || argc > 5) {
        fprintf(stderr, "usage: bench_dem BEDFILE NSTEPS [LAW [ROLLING]]\n");
        return 2;
    }
    dem_contact_law law = DEM_CONTACT_HERTZ_MINDLIN;
    if (argc >= 4 && dem_contact_law_from_name(argv[3], &law) != DEM_OK) {
        fprintf(stderr, "bench_dem: LAW = %s: no such contact law\n", argv[3]);
        return 2;
    }
    int rolling = 1;
    if (argc == 5) {
        if (!strcmp(argv[4], "norolling")) rolling = 0;
        else if (strcmp(argv[4], "rolling")) {
            fprintf(stderr, "bench_dem: ROLLING = %s; allowed: rolling or norolling\n", argv[4]);
            return 2;
        }
    }
    const char *path = argv[1];
    long long nsteps = strtoll(argv[2], NULL, 10);
    if (nsteps <= 0) {
        fprintf(stderr, "bench_dem: NSTEPS = %s, allowed: a positive integer\n", argv[2]);
        return 2;
    }

    long rss0 = status_kb("VmRSS"), hwm0 = status_kb("VmHWM");

    FILE *f = fopen(path, "rb");
    char magic[8];
    int64_t n;
    double lo[3], hi[3];
    if (!f || fread(magic, 1, 8, f) != 8 || memcmp(magic, "DEMBED01", 8) != 0 ||
        fread(&n, sizeof n, 1, f) != 1 || fread(lo, sizeof(double), 3, f) != 3 ||
        fread(hi, sizeof(double), 3, f) != 3 || n <= 0) {
        fprintf(stderr, "bench_dem: %s: not a bed file from bed.py convert (magic DEMBED01)\n", path);
        return 1;
    }

    dem_world *w = NULL;
    if (check(w, dem_world_create(&w), "dem_world_create")) return 1;
    dem_world_set_logger(w, logger, NULL);

    dem_config c;
    dem_config_default(&c);
    c.contact_law = law;
    c.dt = 1.0e-6;
    c.gravity[0] = 0.0; c.gravity[1] = 0.0; c.gravity[2] = -9.81;
    for (int k = 0; k < 3; ++k) {
        c.domain_lo[k] = lo[k];
        c.domain_hi[k] = hi[k];
        c.periodic[k] = 0;
    }
    c.skin = 0.4e-3; /* 0.2 d */
    if (check(w, dem_world_configure(w, &c), "dem_world_configure")) return 1;

    dem_material m;
    memset(&m, 0, sizeof m);
    m.youngs_modulus = 1.0e7;
    m.poisson_ratio = 0.3;
    m.stiffness_n = 0.0;           /* linear law only */
    m.stiffness_t = 0.0;
    m.friction = 0.4;
    m.rolling_friction = rolling ? 0.01 * 0.5e-3 : 0.0; /* 0.01 R*, R* = R/2 = 0.5 mm */
    m.restitution = 0.9;
    m.damping = -1.0;              /* derived from the restitution */
    int mat = -1;
    if (check(w, dem_world_add_material(w, &m, &mat), "dem_world_add_material")) return 1;

    /* six walls, normals pointing into the box */
    const double zero[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < 3; ++k) {
        double p[3] = {0.0, 0.0, 0.0}, nrm[3] = {0.0, 0.0, 0.0};
        int id;
        p[k] = lo[k]; nrm[k] = 1.0;
        if (check(w, dem_world_add_plane(w, p, nrm, mat, zero, &id), "dem_world_add_plane")) return 1;
        p[k] = hi[k]; nrm[k] = -1.0;
        if (check(w, dem_world_add_plane(w, p, nrm, mat, zero, &id), "dem_world_add_plane")) return 1;
    }

    dem_particle *buf = malloc(CHUNK * sizeof *buf);
    if (!buf) { fprintf(stderr, "bench_dem: out of memory\n"); return 1; }
    for (int64_t done = 0; done < n;) {
        size_t k = (size_t)(n - done < CHUNK ? n - done : CHUNK);
        for (size_t i = 0; i < k; ++i) {
            int64_t id;
            double r[11];
            if (fread(&id, sizeof id, 1, f) != 1 || fread(r, sizeof(double), 11, f) != 11) {
                fprintf(stderr, "bench_dem: %s: truncated after %lld of %lld particles\n",
                        path, (long long)(done + (int64_t)i), (long long)n);
                return 1;
            }
            dem_particle *q = &buf[i];
            q->id = id;
            memcpy(q->x, r, 3 * sizeof(double));
            memcpy(q->v, r + 3, 3 * sizeof(double));
            memcpy(q->omega, r + 6, 3 * sizeof(double));
            q->radius = r[9];
            q->density = r[10];
            q->material = mat;
        }
        if (check(w, dem_world_add_particles(w, k, buf), "dem_world_add_particles")) return 1;
        done += (int64_t)k;
    }
    free(buf);
    fclose(f);

    double tc = 0.0;
    if (dem_world_contact_time(w, 1.0, &tc) == DEM_OK)
        printf("ours_contact_time_at_1m_s=%.6g\n", tc);

    double t0 = now();
    if (check(w, dem_world_step(w, 1), "dem_world_step (first, untimed)")) return 1;
    dem_stats s0;
    if (check(w, dem_world_stats(w, &s0), "dem_world_stats")) return 1;
    dem_phase_times p0, p1;
    int prof = dem_world_phase_times(w, &p0) == DEM_OK;
    double t1 = now(), c1 = cpu_now();
    if (check(w, dem_world_step(w, nsteps), "dem_world_step")) return 1;
    double t2 = now(), c2 = cpu_now();
    if (prof) prof = dem_world_phase_times(w, &p1) == DEM_OK;

    dem_stats s;
    if (check(w, dem_world_stats(w, &s), "dem_world_stats")) return 1;
    size_t np = dem_world_count(w);
    int *coord = malloc(np * sizeof *coord);
    double zsum = 0.0;
    if (coord && dem_world_particle_contacts(w, coord, NULL) == DEM_OK)
        for (size_t i = 0; i < np; ++i) zsum += coord[i];
    free(coord);

    long rss1 = status_kb("VmRSS"), hwm1 = status_kb("VmHWM");
    size_t mem_particles = 0, mem_lists = 0;
    int have_mem = dem_world_memory(w, &mem_particles, &mem_lists) == DEM_OK;

    /* bytes per particle in the arrays the API exposes (dem_arrays) */
    size_t api_bytes = sizeof(int64_t) + 3 * 3 * sizeof(double) /* x v omega */
                     + 3 * sizeof(double) /* radius mass density */ + sizeof(int)
                     + 2 * 3 * sizeof(double) /* force_ext torque_ext */
                     + sizeof(double) + 3 * sizeof(double) + 3 * sizeof(double); /* drag */

    printf("ours_contact_law=%s\n", dem_contact_law_name(law));
    printf("ours_rolling_friction=%s\n", rolling ? "rolling (mu_r = 5e-6 m)" : "norolling (mu_r = 0)");
    printf("ours_n=%zu\n", np);
    printf("ours_steps=%lld\n", nsteps);
    printf("ours_first_step_seconds=%.6f\n", t1 - t0);
    printf("ours_loop_seconds=%.6f\n", t2 - t1);
    printf("ours_loop_cpu_seconds=%.6f\n", c2 - c1);
    printf("ours_particle_steps_per_second=%.6g\n", (double)np * (double)nsteps / (t2 - t1));
    printf("ours_list_builds_in_loop=%lld\n", (long long)(s.list_builds - s0.list_builds));
    printf("ours_pair_contacts=%zu\n", s.pair_contacts);
    printf("ours_wall_contacts=%zu\n", s.wall_contacts);
    printf("ours_coordination=%.4f\n", np ? zsum / (double)np : 0.0);
    printf("ours_kinetic_energy=%.6g\n", s.kinetic_energy);
    printf("ours_rotational_energy=%.6g\n", s.rotational_energy);
    printf("ours_max_overlap_ratio=%.6g\n", s.max_overlap_ratio);
    printf("ours_api_arrays_incl_coupling_bytes_per_particle=%zu\n", api_bytes);
    if (have_mem) {
        printf("ours_array_bytes_per_particle=%.1f\n", (double)mem_particles / (double)np);
        printf("ours_list_and_history_bytes_per_particle=%.1f\n", (double)mem_lists / (double)np);
    }
    printf("ours_rss_delta_bytes_per_particle=%.1f\n", 1024.0 * (double)(rss1 - rss0) / (double)np);
    printf("ours_hwm_delta_bytes_per_particle=%.1f\n", 1024.0 * (double)(hwm1 - hwm0) / (double)np);
    printf("ours_log_messages=%ld/%ld/%ld\n", n_log[0], n_log[1], n_log[2]);
    if (prof) {
        const double ph[4] = {p1.integrate - p0.integrate, p1.neighbour - p0.neighbour, p1.pairs - p0.pairs,
                              p1.walls - p0.walls};
        const char *pn[4] = {"integrate", "neighbour", "pairs", "walls"};
        double sum = 0.0;
        for (int k = 0; k < 4; ++k) sum += ph[k];
        for (int k = 0; k < 4; ++k)
            printf("ours_phase_%s_seconds=%.6f   (%.1f %% of the loop, %.2f ns per particle-step)\n", pn[k], ph[k],
                   100.0 * ph[k] / (t2 - t1), 1e9 * ph[k] / ((double)np * (double)nsteps));
        printf("ours_phase_other_seconds=%.6f   (loop minus the four phases: step bookkeeping and timers)\n",
               (t2 - t1) - sum);
    }
    /* FNV-1a digest of the final positions, velocities and spins (storage
       order): equal digests = bit-identical trajectories of two core versions */
    dem_arrays a;
    if (dem_world_arrays(w, &a) == DEM_OK) {
        uint64_t hsh = 1469598103934665603ull;
        const double *arr[3] = {a.x, a.v, a.omega};
        for (int q = 0; q < 3; ++q) {
            const unsigned char *b = (const unsigned char *)arr[q];
            for (size_t k = 0; k < 3 * np * sizeof(double); ++k) { hsh ^= b[k]; hsh *= 1099511628211ull; }
        }
        printf("ours_state_digest=%016llx\n", (unsigned long long)hsh);
    }

    dem_world_destroy(&w);
    return 0;
}
