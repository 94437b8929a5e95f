/* Numbers and names read from text, in one place for every reader (the scene's YAML and the command line):
 * an integer is refused, not cut, when it does not fit the range its key or option allows (strtol's long
 * cast to int made "4294967297" a 1). */
#ifndef IO_TEXT_H
#define IO_TEXT_H

#include <stddef.h>

enum { TEXT_OK = 0, TEXT_NOT_A_NUMBER = 1, TEXT_OUT_OF_RANGE = 2 };

/* A whole decimal integer in [lo, hi] (lo, hi within int): TEXT_OK with *value set, or why not. */
int text_int(const char *text, long long lo, long long hi, int *value);
/* A finite number: TEXT_OK with *value set, or TEXT_NOT_A_NUMBER (also for inf, nan and overflow). */
int text_real(const char *text, double *value);
/* "expected an integer in [lo, hi]" or "expected an integer >= lo" (hi = INT_MAX) ..., for messages. */
void text_int_expected(long long lo, long long hi, char *buf, size_t n);
/* Levenshtein distance with transpositions, capped at 9 (for "misspelt X?" hints). */
int text_distance(const char *a, const char *b);

#endif
