#include "fsutil.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int fs_make_directories(const char *path) {
  char buf[4096];
  if (snprintf(buf, sizeof buf, "%s", path) >= (int)sizeof buf) {
    errno = ENAMETOOLONG;
    return -1;
  }
  for (char *p = buf + 1; *p; p++)
    if (*p == '/') {
      *p = '\0';
      if (mkdir(buf, 0775) && errno != EEXIST) return -1;
      *p = '/';
    }
  if (mkdir(buf, 0775) && errno != EEXIST) return -1;
  struct stat st;
  if (stat(buf, &st)) return -1;
  if (!S_ISDIR(st.st_mode)) {
    errno = ENOTDIR;
    return -1;
  }
  return 0;
}

/* The first existing prefix of 'dir' that is not a directory, or "" */
static void file_in_path(const char *dir, char *out, size_t n) {
  char        buf[4096];
  struct stat st;
  out[0] = '\0';
  snprintf(buf, sizeof buf, "%s", dir);
  size_t len = strlen(buf);
  for (size_t i = 1; i <= len; i++)
    if (buf[i] == '/' || buf[i] == '\0') {
      char c = buf[i];
      buf[i] = '\0';
      int exists = !stat(buf, &st);
      if (exists && !S_ISDIR(st.st_mode)) {
        snprintf(out, n, "%s", buf);
        return;
      }
      buf[i] = c;
      if (!exists) return;
    }
}

int fs_prepare_output_dir(const char *dir, char *err, size_t errlen) {
  char blocker[4096];
  file_in_path(dir, blocker, sizeof blocker);
  if (blocker[0]) {
    if (!strcmp(blocker, dir)) snprintf(err, errlen, "output directory '%s': the output path is a file", dir);
    else snprintf(err, errlen, "output directory '%s': the output path is a file: '%s' is a file, not a directory", dir, blocker);
    return 1;
  }
  if (fs_make_directories(dir)) {
    snprintf(err, errlen, "output directory '%s': cannot create: %s", dir, strerror(errno));
    return 1;
  }
  if (access(dir, W_OK | X_OK)) {
    snprintf(err, errlen, "output directory '%s': not writable: %s", dir, strerror(errno));
    return 1;
  }
  return 0;
}

int fs_copy_file(const char *src, const char *dst) {
  char   part[4200], buf[1 << 16];
  FILE  *in = fopen(src, "rb"), *out;
  size_t n;
  if (!in) return 0;
  snprintf(part, sizeof part, "%s.part", dst);
  if (!(out = fopen(part, "wb"))) return fclose(in), 1;
  while ((n = fread(buf, 1, sizeof buf, in)) > 0)
    if (fwrite(buf, 1, n, out) != n) break;
  int bad = ferror(in) || ferror(out);
  fclose(in);
  bad |= fclose(out) != 0;
  if (!bad && !rename(part, dst)) return 0;
  remove(part);
  return 1;
}
