#include "text.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int text_int(const char *text, long long lo, long long hi, int *value) {
  char *end;
  if (!text) return TEXT_NOT_A_NUMBER;
  while (isspace((unsigned char)*text)) text++;
  if (!*text) return TEXT_NOT_A_NUMBER;
  errno       = 0;
  long long v = strtoll(text, &end, 10);
  if (end == text || *end) return TEXT_NOT_A_NUMBER;
  if (errno == ERANGE || v < lo || v > hi || v < INT_MIN || v > INT_MAX) return TEXT_OUT_OF_RANGE;
  *value = (int)v;
  return TEXT_OK;
}

int text_real(const char *text, double *value) {
  char *end;
  if (!text || !*text) return TEXT_NOT_A_NUMBER;
  errno    = 0;
  double v = strtod(text, &end);
  if (end == text || *end || errno == ERANGE || !isfinite(v)) return TEXT_NOT_A_NUMBER;
  *value = v;
  return TEXT_OK;
}

void text_int_expected(long long lo, long long hi, char *buf, size_t n) {
  if (hi >= INT_MAX && lo <= INT_MIN) snprintf(buf, n, "an integer from %d to %d", INT_MIN, INT_MAX);
  else if (hi >= INT_MAX) snprintf(buf, n, "an integer >= %lld (at most %d)", lo, INT_MAX);
  else snprintf(buf, n, "an integer from %lld to %lld", lo, hi);
}

int text_distance(const char *a, const char *b) {
  size_t la = strlen(a), lb = strlen(b);
  int    d[33][33];
  if (la > 32 || lb > 32) return 9;
  for (size_t i = 0; i <= la; i++) d[i][0] = (int)i;
  for (size_t j = 0; j <= lb; j++) d[0][j] = (int)j;
  for (size_t i = 1; i <= la; i++)
    for (size_t j = 1; j <= lb; j++) {
      int best = d[i - 1][j - 1] + (a[i - 1] != b[j - 1]);
      if (d[i - 1][j] + 1 < best) best = d[i - 1][j] + 1;
      if (d[i][j - 1] + 1 < best) best = d[i][j - 1] + 1;
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] && d[i - 2][j - 2] + 1 < best) best = d[i - 2][j - 2] + 1;
      d[i][j] = best;
    }
  return d[la][lb] < 9 ? d[la][lb] : 9;
}
