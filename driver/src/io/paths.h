/* Input paths of a scene (geometry, .msh, tables) are relative to the scene file's folder, as in a
 * compiler's #include; outputs are relative to the working directory (or -output_dir). */
#ifndef PATHS_H
#define PATHS_H

#include <stddef.h>

/* 'path' unchanged if absolute, else joined to the folder of 'scene_file'. 0, or 1 if it does not fit. */
int path_resolve(const char *scene_file, const char *path, char *out, size_t n);

/* Resolve an input path of a scene and check that the file can be read. 'where' is "file:line: key 'k'"
 * for the message. Returns 0 with out filled, else 1 with err filled.
 * Transition: a relative path that exists only relative to the working directory (the old rule) is
 * still accepted, with a warning on stderr that says how to write it; path_cwd_fallback(0) turns that
 * off (an error instead). */
int  path_input(const char *scene_file, const char *where, const char *path, char *out, size_t n, char *err,
                size_t errlen);
void path_cwd_fallback(int on);

#endif
