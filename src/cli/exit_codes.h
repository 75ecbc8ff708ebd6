/* The exit codes of every refray command: one table (README "Exit codes"), OpenImageIO idiff's
 * numbering extended to all commands, so that grading scripts written for idiff keep working. */
#ifndef REFRAY_CLI_EXIT_CODES_H
#define REFRAY_CLI_EXIT_CODES_H

enum {
    RF_EXIT_OK = 0,    /* success; diff/grade/--check: pass */
    RF_EXIT_WARN = 1,  /* passed with warnings (diff/grade above the warn threshold only) */
    RF_EXIT_FAIL = 2,  /* the answer is wrong or cannot be computed: images differ, a --check line
                          mismatches, a singular matrix, a render with non-finite pixels */
    RF_EXIT_SIZE = 3,  /* images of different size or channels */
    RF_EXIT_FILE = 4,  /* a file is missing, unreadable or malformed (scene, image, batch file), or
                          an output cannot be written */
    RF_EXIT_USAGE = 5  /* usage: unknown command/option/formula id/input, a missing, duplicate or
                          malformed value */
};
/* 130 / 143: stopped by SIGINT / SIGTERM after the checkpoint was written (render --checkpoint) */

#endif
