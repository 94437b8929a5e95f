/* The run's JSON files (json_write.h). */
#include "json_write.h"

#include <errno.h>
#include <math.h>
#include <string.h>

void json_num(FILE *fp, double v) {
  if (isfinite(v)) fprintf(fp, "%.10g", v);
  else fputs("null", fp);
}

void json_str(FILE *fp, const char *v) {
  fputc('"', fp);
  for (const unsigned char *c = (const unsigned char *)v; *c; c++) {
    if (*c == '"' || *c == '\\') fprintf(fp, "\\%c", *c);
    else if (*c < 0x20) fprintf(fp, "\\u%04x", *c);
    else fputc(*c, fp);
  }
  fputc('"', fp);
}

void json_summary_head(FILE *fp, const char *scene, const char *kind, int completed) {
  fputs("{\n  \"scene\": ", fp);
  json_str(fp, scene);
  fputs(", \"kind\": ", fp);
  json_str(fp, kind);
  fprintf(fp, ", \"completed\": %s", completed ? "true" : "false");
}

FILE *json_file_open(const char *dir, const char *name, char *part, size_t n, char *err, size_t errlen) {
  snprintf(part, n, "%s/%s.part", dir, name);
  FILE *fp = fopen(part, "w");
  if (!fp) snprintf(err, errlen, "%s: cannot write: %s", part, strerror(errno));
  return fp;
}

int json_file_close(FILE *fp, const char *part, int final, char *err, size_t errlen) {
  char   path[1200];
  size_t len = strlen(part);
  snprintf(path, sizeof path, "%.*s", (int)(len > 5 && final ? len - 5 : len), part); /* without ".part" */
  fputs("\n}\n", fp);
  if (fclose(fp) || (final && rename(part, path))) {
    snprintf(err, errlen, "%s: cannot write: %s", path, strerror(errno));
    return 1;
  }
  return 0;
}
