/* refray render --deps FILE: a make dependency file, as a compiler's -MD -MP writes one. */
#ifndef REFRAY_CLI_DEPFILE_H
#define REFRAY_CLI_DEPFILE_H

#include <stddef.h>

/* "T1 T2: P1 P2 ...\n" followed by "P:\n" for every prerequisite (so that make goes on when
 * one is deleted instead of failing: -MP), names escaped for make (space, '#', '$'); targets
 * that are NULL are left out. malloc'ed; NULL when out of memory. */
char *rf_depfile_text(const char *const *targets, int n_targets, char *const *prereqs, size_t n_prereqs);
/* Writes text to path through a temporary file renamed over it: a make run never includes half
 * a file. 0 and a message in err on failure. */
int rf_depfile_write(const char *path, const char *text, char *err, size_t errsz);

#endif
