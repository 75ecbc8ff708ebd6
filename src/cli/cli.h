/* The subcommands of the `refray` command. Each returns the process exit code. */
#ifndef REFRAY_CLI_H
#define REFRAY_CLI_H

#include <stdio.h>

int rf_cmd_formula(int argc, char **argv);

#endif
