#include "fe_checkpoint.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CHECKPOINT_MAGIC 0x43433943 /* "CC9C" */

static void checkpoint_path(const FeScene *sc, int rank, char *path, size_t n) {
  snprintf(path, n, "%s/checkpoint.rank%d.bin", sc->outdir, rank);
}

/* One file per rank, written to a temporary name and renamed, so a crash never leaves half a file. */
int write_checkpoint(const FeScene *sc, FeProblem *p, Vec U, const Progress *pr, long history_offset,
                            char *err, size_t errlen) {
  PetscMPIInt rank, size;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  char path[700], tmp[710];
  checkpoint_path(sc, rank, path, sizeof path);
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  FILE *fp = fopen(tmp, "wb");
  if (!fp) {
    snprintf(err, errlen, "%s: cannot write the checkpoint: %s", tmp, strerror(errno));
    return 1;
  }
  PetscInt           nloc, npoint = p->npoint, nsv = p->nsv;
  const PetscScalar *u;
  int                magic = CHECKPOINT_MAGIC;
  VecGetLocalSize(U, &nloc);
  VecGetArrayRead(U, &u);
  fwrite(&magic, sizeof magic, 1, fp);
  fwrite(&size, sizeof size, 1, fp);
  fwrite(pr, sizeof *pr, 1, fp);
  fwrite(pr->out_times, sizeof(PetscReal), (size_t)pr->nout, fp);
  fwrite(&history_offset, sizeof history_offset, 1, fp);
  fwrite(&p->umat_calls, sizeof p->umat_calls, 1, fp);
  fwrite(&nloc, sizeof nloc, 1, fp);
  fwrite(u, sizeof(PetscScalar), (size_t)nloc, fp);
  fwrite(&npoint, sizeof npoint, 1, fp);
  fwrite(&nsv, sizeof nsv, 1, fp);
  fwrite(p->state, sizeof(PetscReal), (size_t)(npoint * nsv), fp);
  fwrite(&magic, sizeof magic, 1, fp);
  VecRestoreArrayRead(U, &u);
  if (fclose(fp) || rename(tmp, path)) {
    snprintf(err, errlen, "%s: cannot write the checkpoint: %s", path, strerror(errno));
    return 1;
  }
  return 0;
}

int read_checkpoint(const FeScene *sc, FeProblem *p, Vec U, Progress *pr, long *history_offset, char *err,
                           size_t errlen) {
  PetscMPIInt rank, size, saved_size;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  char path[700];
  checkpoint_path(sc, rank, path, sizeof path);
  FILE *fp = fopen(path, "rb");
  if (!fp) {
    snprintf(err, errlen, "-restart: %s: cannot open: %s (run with -checkpoint_every N first)", path, strerror(errno));
    return 1;
  }
  int         magic = 0, end = 0, ok = 1;
  PetscInt    nloc, mine, npoint, nsv;
  PetscScalar *u;
  ok &= fread(&magic, sizeof magic, 1, fp) == 1 && magic == CHECKPOINT_MAGIC;
  ok &= fread(&saved_size, sizeof saved_size, 1, fp) == 1;
  if (ok && saved_size != size) {
    fclose(fp);
    snprintf(err, errlen, "-restart: %s was written by %d ranks; restart with mpiexec -n %d", path, saved_size, saved_size);
    return 1;
  }
  ok &= fread(pr, sizeof *pr, 1, fp) == 1;
  if (ok) {
    pr->out_times = malloc(sizeof(PetscReal) * (size_t)(pr->nout > 0 ? pr->nout : 1));
    ok &= fread(pr->out_times, sizeof(PetscReal), (size_t)pr->nout, fp) == (size_t)pr->nout;
  }
  ok &= fread(history_offset, sizeof *history_offset, 1, fp) == 1;
  ok &= fread(&p->umat_calls, sizeof p->umat_calls, 1, fp) == 1;
  ok &= fread(&nloc, sizeof nloc, 1, fp) == 1;
  VecGetLocalSize(U, &mine);
  if (ok && nloc != mine) {
    fclose(fp);
    snprintf(err, errlen, "-restart: %s holds %d unknowns on this rank, the scene gives %d: not the same scene or mesh",
             path, (int)nloc, (int)mine);
    return 1;
  }
  VecGetArray(U, &u);
  ok &= fread(u, sizeof(PetscScalar), (size_t)nloc, fp) == (size_t)nloc;
  VecRestoreArray(U, &u);
  ok &= fread(&npoint, sizeof npoint, 1, fp) == 1 && fread(&nsv, sizeof nsv, 1, fp) == 1;
  ok &= npoint == p->npoint && nsv == p->nsv;
  ok &= ok && fread(p->state, sizeof(PetscReal), (size_t)(npoint * nsv), fp) == (size_t)(npoint * nsv);
  ok &= fread(&end, sizeof end, 1, fp) == 1 && end == CHECKPOINT_MAGIC;
  fclose(fp);
  if (!ok) {
    snprintf(err, errlen, "-restart: %s is not a complete checkpoint of this scene", path);
    return 1;
  }
  memcpy(p->trial, p->state, sizeof(PetscReal) * (size_t)(npoint * nsv));
  return 0;
}
