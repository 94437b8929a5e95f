/* Output directories: created on demand, and checked before anything is written into them. */
#ifndef FSUTIL_H
#define FSUTIL_H

#include <stddef.h>

/* mkdir -p; 0 on success, else -1 with errno set (ENOTDIR when a component is a file). */
int fs_make_directories(const char *path);

/* Make 'dir' (and its parents) and check that a file can be created in it, touching nothing already
 * there. 0, or 1 with err filled: "output directory 'D': the output path is a file" (or a component of
 * it is: named), "...: cannot create: <reason>", "...: not writable: <reason>". */
int fs_prepare_output_dir(const char *dir, char *err, size_t errlen);

/* Copy src to dst through dst.part, renamed into place once whole (a reader never sees half a file; on failure the
 * .part is removed and dst untouched). A missing src copies nothing. 0, or 1. */
int fs_copy_file(const char *src, const char *dst);

#endif
