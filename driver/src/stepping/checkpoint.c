#include "checkpoint.h"

#include "../io/log_events.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#define CKPT_MAGIC 0x43433952 /* "CC9R" */
#define CKPT_VERSION 10 /* 4: the indenter's counters as integers (semismooth_state_io); 5: reported quantities and the mesh's hash in RunState; 6: their time-step errors;
                          7: a point's UMAT call count in its state (PointSummary.umat_calls), and the one history layout (a point's
                          segment column is stage, an FE history has stage_name: a format-6 checkpoint's history.csv has the old one);
                          8: the cutbacks by their cause in RunState; 9: the outputs at the stage's start in RunState;
                          10: the rejected attempt's estimate size beside its ratio (stage_runner.c, judge: a jump told apart), the jumps */

static void set_path(const RunnerOptions *opt, int step, int rank, char *path, size_t n) {
  snprintf(path, n, "%s/checkpoint.%d.rank%d.bin", opt->outdir, step, rank);
}

/* The set's shared file (the solver's distributed state, written and read by all ranks together). */
static void shared_path(const RunnerOptions *opt, int step, char *path, size_t n) {
  snprintf(path, n, "%s/checkpoint.%d.h5", opt->outdir, step);
}

static int all_ok(MPI_Comm comm, int ok) {
  int all = 0;
  MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, comm);
  return all;
}

/* The sets before this one are no longer needed: this rank's files of every other step (also those a kill
   between the two renames left behind); rank 0: the shared files of the other steps, and the files of ranks a
   run on more ranks left (a restart on fewer). */
static void remove_older_sets(const RunnerOptions *opt, int rank, int size, int step) {
  DIR           *dir = opendir(opt->outdir);
  struct dirent *e;
  if (!dir) return;
  while ((e = readdir(dir))) {
    int  s, r, n = 0;
    char path[1100];
    if (sscanf(e->d_name, "checkpoint.%d.rank%d.bin%n", &s, &r, &n) == 2 && !e->d_name[n] && (r == rank || (!rank && r >= size)) &&
        s != step) {
      set_path(opt, s, r, path, sizeof path);
      remove(path);
    }
    n = 0;
    if (!rank && sscanf(e->d_name, "checkpoint.%d.h5%n", &s, &n) == 1 && (!e->d_name[n] || !strcmp(e->d_name + n, ".tmp")) && s != step) {
      snprintf(path, sizeof path, "%s/%s", opt->outdir, e->d_name);
      remove(path);
    }
  }
  closedir(dir);
}

/* The solver's shared file, written by all ranks to a temporary name; rank 0 syncs it to disk and renames it. */
static int write_shared(StepSolver *sv, const RunnerOptions *opt, int step, char *err, size_t errlen) {
  char path[1100], tmp[1110];
  int  rank, ok;
  MPI_Comm_rank(sv->comm, &rank);
  shared_path(opt, step, path, sizeof path);
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  ok = !sv->save_shared(sv->ctx, tmp);
  if (all_ok(sv->comm, ok) && !rank) {
    int fd = open(tmp, O_RDONLY);
    ok = fd >= 0 && !fsync(fd);
    if (fd >= 0) close(fd);
    ok = ok && !rename(tmp, path);
  }
  if (!all_ok(sv->comm, ok)) {
    snprintf(err, errlen, "%s: cannot write the checkpoint's shared file; the previous checkpoint is kept", path);
    if (!rank) remove(tmp);
    return 1;
  }
  return 0;
}

static int write_set(StepSolver *sv, const RunnerOptions *opt, RunState *st, int *last, char *err, size_t errlen);

int checkpoint_write(StepSolver *sv, const RunnerOptions *opt, RunState *st, int *last, char *err, size_t errlen) {
  PetscErrorCode ierr = PetscLogEventBegin(driver_event(EV_CHECKPOINT), 0, 0, 0, 0);
  int            rc   = ierr ? stage_runner_status(ierr, err) : write_set(sv, opt, st, last, err, errlen);
  ierr                = PetscLogEventEnd(driver_event(EV_CHECKPOINT), 0, 0, 0, 0);
  return rc ? rc : stage_runner_status(ierr, err);
}

static int write_set(StepSolver *sv, const RunnerOptions *opt, RunState *st, int *last, char *err, size_t errlen) {
  int rank, size;
  MPI_Comm_rank(sv->comm, &rank);
  MPI_Comm_size(sv->comm, &size);
  long off = st->history_offset;
  MPI_Bcast(&off, 1, MPI_LONG, 0, sv->comm); /* rank 0 holds the history */
  st->history_offset = off;
  char path[1100], tmp[1110];
  if (sv->save_shared && write_shared(sv, opt, st->step, err, errlen)) return 1;
  set_path(opt, st->step, rank, path, sizeof path);
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  unsigned long long hash = binfile_hash(opt->scene_file);
  BinFile            f;
  int                magic = CKPT_MAGIC, version = CKPT_VERSION;
  binfile_open(&f, tmp, "wb");
  binfile_write(&f, &magic, sizeof magic, 1);
  binfile_write(&f, &version, sizeof version, 1);
  binfile_write(&f, &size, sizeof size, 1);
  binfile_write(&f, &rank, sizeof rank, 1);
  binfile_write(&f, &hash, sizeof hash, 1);
  binfile_write(&f, st, sizeof *st, 1);
  if (f.ok && sv->save(sv->ctx, &f)) f.ok = 0;
  binfile_write(&f, &magic, sizeof magic, 1);
  int ok = !binfile_close(&f, 1) && !rename(tmp, path);
  if (!all_ok(sv->comm, ok)) {
    snprintf(err, errlen, "%s: cannot write the checkpoint (%s on this or another rank); the previous one is kept", path,
             ok ? "failed" : strerror(errno));
    remove(tmp);
    return 1;
  }
  if (!rank) { /* the set is complete on every rank: make it the latest */
    char latest[1100], ltmp[1110];
    snprintf(latest, sizeof latest, "%s/checkpoint.latest", opt->outdir);
    snprintf(ltmp, sizeof ltmp, "%s.tmp", latest);
    BinFile l;
    ok = !binfile_open(&l, ltmp, "w");
    if (ok) ok = fprintf(l.fp, "%d %d\n", st->step, size) > 0;
    ok = !binfile_close(&l, 1) && ok && !rename(ltmp, latest);
  }
  if (!all_ok(sv->comm, ok)) {
    snprintf(err, errlen, "%s/checkpoint.latest: cannot write; the previous checkpoint is kept", opt->outdir);
    return 1;
  }
  remove_older_sets(opt, rank, size, st->step);
  *last = st->step;
  return 0;
}

/* The step of the latest set (rank 0 reads it; every rank gets it). */
static int latest_step(StepSolver *sv, const RunnerOptions *opt, int *step, int *nranks) {
  int rank, v[2] = {-1, 0};
  MPI_Comm_rank(sv->comm, &rank);
  if (!rank) {
    char path[1100];
    snprintf(path, sizeof path, "%s/checkpoint.latest", opt->outdir);
    FILE *fp = fopen(path, "r");
    if (fp) {
      if (fscanf(fp, "%d %d", &v[0], &v[1]) != 2) v[0] = -2;
      fclose(fp);
    }
  }
  MPI_Bcast(v, 2, MPI_INT, 0, sv->comm);
  *step = v[0], *nranks = v[1];
  return v[0] >= 0;
}

/* The message of a checkpoint this run cannot continue (code: 1 missing or damaged, on rank 'bad' first; 2 another
   scene; 3 another format, 'other'; 4 another mesh). */
static void refusal_message(int code, int step, int bad, int other, const RunnerOptions *opt, char *err, size_t errlen) {
  if (code == 2)
    snprintf(err, errlen, "-restart: the scene %s differs from the one the checkpoint in %s was written for (material, loads or "
                          "stages changed): run it afresh, without -restart; nothing was written", opt->scene_file, opt->outdir);
  else if (code == 4)
    snprintf(err, errlen, "-restart: the checkpoint of step %d in %s was written on another mesh than %s (the mesh file differs: a "
                          "changed .geo, other gmsh parameters or another gmsh): run the scene afresh, without -restart; nothing was written",
             step, opt->outdir, opt->mesh_file ? opt->mesh_file : "this run's");
  else if (code == 3)
    snprintf(err, errlen, "-restart: the checkpoint of step %d in %s was written by another version of the driver (checkpoint "
                          "format %d; this driver reads format %d): %s; nothing was written", step, opt->outdir, other, CKPT_VERSION,
             other < CKPT_VERSION ? "a checkpoint of an older layout (its state and the history's columns are not this driver's) "
                                    "cannot be continued: run the scene again from its start, without -restart"
                                  : "a newer driver's: continue it with that driver, or run the scene again from its start without -restart");
  else
    snprintf(err, errlen, "-restart: the checkpoint of step %d in %s is missing or incomplete on at least one rank (first: rank %d, "
                          "checkpoint.%d.rank%d.bin): nothing was written", step, opt->outdir, bad, step, bad);
}

static void latest_missing_message(const RunnerOptions *opt, char *err, size_t errlen) {
  snprintf(err, errlen, "-restart: %s/checkpoint.latest is missing or damaged (run with -checkpoint_every N first)", opt->outdir);
}

/* The head of rank 'rank's file, open in f: its magic, format, ranks and rank, the scene's hash and the runner's
   state. 0 (this run's), 1 (damaged), 2 (another scene), 3 (another format, in *version) or 4 (another mesh). */
static int read_head(BinFile *f, const RunnerOptions *opt, int nranks, int rank, int *version, RunState *st) {
  unsigned long long hash = 0;
  binfile_expect_int(f, CKPT_MAGIC);
  binfile_read(f, version, sizeof *version, 1);
  if (f->ok && *version != CKPT_VERSION) {
    f->ok = 0;
    return 3;
  }
  binfile_expect_int(f, nranks);
  binfile_expect_int(f, rank);
  binfile_read(f, &hash, sizeof hash, 1);
  binfile_read(f, st, sizeof *st, 1);
  if (!f->ok) return 1;
  if (hash != binfile_hash(opt->scene_file)) return 2;
  return st->mesh_hash != binfile_hash(opt->mesh_file) ? 4 : 0;
}

int checkpoint_precheck(const RunnerOptions *opt, char *err, size_t errlen) {
  char     path[1100];
  int      step = -1, nranks = 0, version = 0, code = 1;
  RunState st;
  BinFile  f;
  snprintf(path, sizeof path, "%s/checkpoint.latest", opt->outdir);
  FILE *fp = fopen(path, "r");
  if (fp && fscanf(fp, "%d %d", &step, &nranks) != 2) step = -1;
  if (fp) fclose(fp);
  if (step < 0) {
    latest_missing_message(opt, err, errlen);
    return 1;
  }
  set_path(opt, step, 0, path, sizeof path);
  if (!binfile_open(&f, path, "rb")) {
    code = read_head(&f, opt, nranks, 0, &version, &st);
    binfile_close(&f, 0);
  }
  if (code) refusal_message(code, step, 0, version, opt, err, errlen);
  return code >= 2 ? 2 : code;
}

int checkpoint_read(StepSolver *sv, const RunnerOptions *opt, RunState *st, int *last, char *err, size_t errlen) {
  int rank, size, step, nranks;
  MPI_Comm_rank(sv->comm, &rank);
  MPI_Comm_size(sv->comm, &size);
  if (!latest_step(sv, opt, &step, &nranks)) {
    latest_missing_message(opt, err, errlen);
    return 1;
  }
  if (nranks != size && !sv->load_shared) {
    snprintf(err, errlen, "-restart: the checkpoint in %s was written by %d ranks; restart with mpiexec -n %d", opt->outdir, nranks,
             nranks);
    return 2;
  }
  /* Each rank reads its own file; on another number of ranks (the distributed state is in the shared file) the
     ranks beyond the writers read rank 0's, which holds the same values. */
  int                from = rank < nranks ? rank : 0;
  char               path[1100];
  BinFile            f;
  int                code = 1, version = CKPT_VERSION; /* read_head's codes */
  set_path(opt, step, from, path, sizeof path);
  if (!binfile_open(&f, path, "rb")) {
    code = read_head(&f, opt, nranks, from, &version, st);
    if (!code && sv->load(sv->ctx, &f)) f.ok = 0;
    binfile_expect_int(&f, CKPT_MAGIC);
    if (binfile_close(&f, 0) && !code) code = 1;
    if (!code && st->step != step) code = 1;
  }
  int worst = 0, mine = code ? from : nranks, first_bad = nranks, found = code == 3 ? version : 0, other = 0;
  MPI_Allreduce(&code, &worst, 1, MPI_INT, MPI_MAX, sv->comm);
  MPI_Allreduce(&mine, &first_bad, 1, MPI_INT, MPI_MIN, sv->comm);
  MPI_Allreduce(&found, &other, 1, MPI_INT, MPI_MAX, sv->comm);
  if (worst) refusal_message(worst, step, first_bad, other, opt, err, errlen);
  if (worst) return worst >= 2 ? 2 : worst;
  if (sv->load_shared) {
    shared_path(opt, step, path, sizeof path);
    if (sv->load_shared(sv->ctx, path)) {
      snprintf(err, errlen, "-restart: %s (written by %d ranks) cannot be read into this run's mesh on %d (a mesh or contact surface "
                            "other than the checkpointed run's?): nothing was written", path, nranks, size);
      return 1;
    }
  }
  if (sv->resume && sv->resume(sv->ctx)) {
    snprintf(err, errlen, "-restart: the state of the checkpoint of step %d in %s could not be set up", step, opt->outdir);
    return 1;
  }
  *last = step;
  if (!rank && !opt->quiet)
    printf("restart at step %d, t = %g s (stage %d)%s\n", st->step, st->t, st->stage, nranks != size ? ", on another number of ranks" : "");
  if (!rank && !opt->quiet && nranks != size) printf("  the checkpoint was written by %d ranks, this run has %d\n", nranks, size);
  return 0;
}
