/* Binary files with every write and read checked: a BinFile remembers the first failure, so a sequence
 * of writes needs one check at the end (binfile_close). Only plain values and arrays go in: never a
 * struct holding pointers. */
#ifndef BINFILE_H
#define BINFILE_H

#include <stdio.h>

typedef struct {
  FILE *fp;
  int   ok;
} BinFile;

int  binfile_open(BinFile *f, const char *path, const char *mode); /* 0 on success */
void binfile_write(BinFile *f, const void *p, size_t size, size_t n);
void binfile_read(BinFile *f, void *p, size_t size, size_t n);
/* Read an int and require it to equal 'expected' (a magic number, a size). */
void binfile_expect_int(BinFile *f, int expected);
/* Close; a file written is flushed to disk (fsync) before it counts as written. 0 when every call succeeded. */
int binfile_close(BinFile *f, int sync);
/* 64-bit FNV-1a of a file's bytes (0 if it cannot be read): to tell whether a scene changed. */
unsigned long long binfile_hash(const char *path);

#endif
