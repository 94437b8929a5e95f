#include "binfile.h"

#include <unistd.h>

int binfile_open(BinFile *f, const char *path, const char *mode) {
  f->fp = fopen(path, mode);
  f->ok = f->fp != NULL;
  return !f->ok;
}

void binfile_write(BinFile *f, const void *p, size_t size, size_t n) {
  if (f->ok && n) f->ok = fwrite(p, size, n, f->fp) == n;
}

void binfile_read(BinFile *f, void *p, size_t size, size_t n) {
  if (f->ok && n) f->ok = fread(p, size, n, f->fp) == n;
}

void binfile_expect_int(BinFile *f, int expected) {
  int v = expected + 1;
  binfile_read(f, &v, sizeof v, 1);
  if (v != expected) f->ok = 0;
}

int binfile_close(BinFile *f, int sync) {
  if (!f->fp) return 1;
  if (sync && f->ok) f->ok = fflush(f->fp) == 0 && fsync(fileno(f->fp)) == 0;
  if (fclose(f->fp)) f->ok = 0;
  f->fp = NULL;
  return !f->ok;
}

unsigned long long binfile_hash(const char *path) {
  FILE *fp = path ? fopen(path, "rb") : NULL;
  if (!fp) return 0;
  unsigned long long h = 1469598103934665603ULL;
  int                c;
  while ((c = fgetc(fp)) != EOF) h = (h ^ (unsigned char)c) * 1099511628211ULL;
  fclose(fp);
  return h;
}
