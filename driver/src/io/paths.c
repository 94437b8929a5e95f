#include "paths.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static int cwd_fallback = 1;

void path_cwd_fallback(int on) { cwd_fallback = on; }

int path_resolve(const char *scene_file, const char *path, char *out, size_t n) {
  const char *slash = strrchr(scene_file, '/');
  int         len;
  if (path[0] == '/' || !slash) len = snprintf(out, n, "%s", path);
  else len = snprintf(out, n, "%.*s/%s", (int)(slash - scene_file), scene_file, path);
  return len < 0 || (size_t)len >= n;
}

/* 0 if a readable regular file; else errno-like reason in *why. */
static int readable_file(const char *path, const char **why) {
  struct stat st;
  if (stat(path, &st)) {
    *why = strerror(errno);
    return 1;
  }
  if (S_ISDIR(st.st_mode)) {
    *why = "it is a directory";
    return 1;
  }
  if (access(path, R_OK)) {
    *why = strerror(errno);
    return 1;
  }
  return 0;
}

int path_input(const char *scene_file, const char *where, const char *path, char *out, size_t n, char *err,
               size_t errlen) {
  const char *why = "";
  if (!path[0]) {
    snprintf(err, errlen, "%s: expected a file name, got ''", where);
    return 1;
  }
  if (path_resolve(scene_file, path, out, n)) {
    snprintf(err, errlen, "%s: the path '%s' is too long", where, path);
    return 1;
  }
  if (!readable_file(out, &why)) return 0;
  const char *why_cwd = "";
  if (cwd_fallback && path[0] != '/' && strcmp(out, path) && !readable_file(path, &why_cwd)) {
    fprintf(stderr,
            "driver: warning: %s: '%s' is not in the scene file's folder; using it from the working directory "
            "(deprecated: paths in a scene are relative to the scene file, write it so or give an absolute path)\n",
            where, path);
    snprintf(out, n, "%s", path);
    return 0;
  }
  if (strcmp(out, path))
    snprintf(err, errlen, "%s: cannot open '%s' (as '%s': paths in a scene are relative to the scene file's folder): %s",
             where, path, out, why);
  else snprintf(err, errlen, "%s: cannot open '%s': %s", where, path, why);
  return 1;
}
