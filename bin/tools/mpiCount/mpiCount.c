/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Description
    MPI profiling shim (the standard PMPI interface, loaded with LD_PRELOAD
    by bin/tools/mpiMessageCount): counts the point-to-point messages and
    bytes each rank sends to each other rank, and the collective calls,
    inside the DEM sub-steps of a decomposed run.  demFoam marks those with
    MPI_Pcontrol(2, m) on entry (m DEM steps follow) and MPI_Pcontrol(1) on
    exit (processorGhosts::step); outside them nothing is counted.  Each
    rank writes mpiCount.<rank> in the working directory at MPI_Finalize.

\*---------------------------------------------------------------------------*/

#include <mpi.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#define MAXRANK 4096
#define NCOLL 16

static int inDem = 0;
static long long demSteps = 0, demCalls = 0;
static long long msgs[MAXRANK], bytes[MAXRANK];
static const char *collName[NCOLL];
static long long collCount[NCOLL];

static void countSend(int count, MPI_Datatype type, int dest, MPI_Comm comm)
{
    if (!inDem || dest < 0) return;
    /* the destination as a rank of MPI_COMM_WORLD */
    MPI_Group g, w;
    int wr = -1, size = 0;
    PMPI_Comm_group(comm, &g);
    PMPI_Comm_group(MPI_COMM_WORLD, &w);
    PMPI_Group_translate_ranks(g, 1, &dest, w, &wr);
    PMPI_Group_free(&g);
    PMPI_Group_free(&w);
    PMPI_Type_size(type, &size);
    if (wr >= 0 && wr < MAXRANK) {
        msgs[wr]++;
        bytes[wr] += (long long)count * size;
    }
}

static void countColl(const char *name)
{
    if (!inDem) return;
    for (int k = 0; k < NCOLL; ++k) {
        if (!collName[k]) collName[k] = name;
        if (collName[k] == name || !strcmp(collName[k], name)) {
            collCount[k]++;
            return;
        }
    }
}

int MPI_Pcontrol(const int level, ...)
{
    if (level == 2) {
        va_list ap;
        va_start(ap, level);
        demSteps += va_arg(ap, int);
        va_end(ap);
        demCalls++;
        inDem = 1;
    } else {
        inDem = 0;
    }
    return MPI_SUCCESS;
}

/* point-to-point sends */
#define SEND(NAME, ...) \
    countSend(count, type, dest, comm); return P##NAME(__VA_ARGS__)
int MPI_Send(const void *b, int count, MPI_Datatype type, int dest, int tag, MPI_Comm comm)
{ SEND(MPI_Send, b, count, type, dest, tag, comm); }
int MPI_Ssend(const void *b, int count, MPI_Datatype type, int dest, int tag, MPI_Comm comm)
{ SEND(MPI_Ssend, b, count, type, dest, tag, comm); }
int MPI_Bsend(const void *b, int count, MPI_Datatype type, int dest, int tag, MPI_Comm comm)
{ SEND(MPI_Bsend, b, count, type, dest, tag, comm); }
int MPI_Rsend(const void *b, int count, MPI_Datatype type, int dest, int tag, MPI_Comm comm)
{ SEND(MPI_Rsend, b, count, type, dest, tag, comm); }
int MPI_Isend(const void *b, int count, MPI_Datatype type, int dest, int tag, MPI_Comm comm, MPI_Request *r)
{ SEND(MPI_Isend, b, count, type, dest, tag, comm, r); }
int MPI_Issend(const void *b, int count, MPI_Datatype type, int dest, int tag, MPI_Comm comm, MPI_Request *r)
{ SEND(MPI_Issend, b, count, type, dest, tag, comm, r); }

/* collectives */
#define COLL(NAME, ...) countColl(#NAME); return P##NAME(__VA_ARGS__)
int MPI_Barrier(MPI_Comm c) { COLL(MPI_Barrier, c); }
int MPI_Bcast(void *b, int n, MPI_Datatype t, int root, MPI_Comm c)
{ COLL(MPI_Bcast, b, n, t, root, c); }
int MPI_Reduce(const void *s, void *r, int n, MPI_Datatype t, MPI_Op op, int root, MPI_Comm c)
{ COLL(MPI_Reduce, s, r, n, t, op, root, c); }
int MPI_Allreduce(const void *s, void *r, int n, MPI_Datatype t, MPI_Op op, MPI_Comm c)
{ COLL(MPI_Allreduce, s, r, n, t, op, c); }
int MPI_Iallreduce(const void *s, void *r, int n, MPI_Datatype t, MPI_Op op, MPI_Comm c, MPI_Request *q)
{ COLL(MPI_Iallreduce, s, r, n, t, op, c, q); }
int MPI_Alltoall(const void *s, int sn, MPI_Datatype st, void *r, int rn, MPI_Datatype rt, MPI_Comm c)
{ COLL(MPI_Alltoall, s, sn, st, r, rn, rt, c); }
int MPI_Alltoallv(const void *s, const int *sn, const int *sd, MPI_Datatype st, void *r, const int *rn, const int *rd, MPI_Datatype rt, MPI_Comm c)
{ COLL(MPI_Alltoallv, s, sn, sd, st, r, rn, rd, rt, c); }
int MPI_Allgather(const void *s, int sn, MPI_Datatype st, void *r, int rn, MPI_Datatype rt, MPI_Comm c)
{ COLL(MPI_Allgather, s, sn, st, r, rn, rt, c); }
int MPI_Allgatherv(const void *s, int sn, MPI_Datatype st, void *r, const int *rn, const int *rd, MPI_Datatype rt, MPI_Comm c)
{ COLL(MPI_Allgatherv, s, sn, st, r, rn, rd, rt, c); }
int MPI_Gather(const void *s, int sn, MPI_Datatype st, void *r, int rn, MPI_Datatype rt, int root, MPI_Comm c)
{ COLL(MPI_Gather, s, sn, st, r, rn, rt, root, c); }
int MPI_Gatherv(const void *s, int sn, MPI_Datatype st, void *r, const int *rn, const int *rd, MPI_Datatype rt, int root, MPI_Comm c)
{ COLL(MPI_Gatherv, s, sn, st, r, rn, rd, rt, root, c); }
int MPI_Scatter(const void *s, int sn, MPI_Datatype st, void *r, int rn, MPI_Datatype rt, int root, MPI_Comm c)
{ COLL(MPI_Scatter, s, sn, st, r, rn, rt, root, c); }
int MPI_Scatterv(const void *s, const int *sn, const int *sd, MPI_Datatype st, void *r, int rn, MPI_Datatype rt, int root, MPI_Comm c)
{ COLL(MPI_Scatterv, s, sn, sd, st, r, rn, rt, root, c); }
int MPI_Scan(const void *s, void *r, int n, MPI_Datatype t, MPI_Op op, MPI_Comm c)
{ COLL(MPI_Scan, s, r, n, t, op, c); }

int MPI_Finalize(void)
{
    int me = 0, np = 1;
    PMPI_Comm_rank(MPI_COMM_WORLD, &me);
    PMPI_Comm_size(MPI_COMM_WORLD, &np);
    char name[64];
    snprintf(name, sizeof name, "mpiCount.%d", me);
    FILE *f = fopen(name, "w");
    if (f) {
        fprintf(f, "rank %d of %d\ndemSteps %lld\ndemCalls %lld\n", me, np, demSteps, demCalls);
        for (int r = 0; r < np && r < MAXRANK; ++r)
            if (msgs[r]) fprintf(f, "send %d %lld %lld\n", r, msgs[r], bytes[r]);
        for (int k = 0; k < NCOLL && collName[k]; ++k)
            fprintf(f, "collective %s %lld\n", collName[k], collCount[k]);
        fclose(f);
    }
    return PMPI_Finalize();
}
