/* The subcommands of the `refray` command. Each returns the process exit code. */
#ifndef REFRAY_CLI_H
#define REFRAY_CLI_H

#include <stdio.h>

int rf_cmd_formula(int argc, char **argv);
int rf_cmd_chromaticity(int argc, char **argv); /* both in cmd_chromaticity.c */
int rf_cmd_metamers(int argc, char **argv);
int rf_cmd_info(int argc, char **argv);
int rf_cmd_render(int argc, char **argv);
int rf_cmd_merge(int argc, char **argv);
int rf_cmd_trace(int argc, char **argv);
int rf_cmd_diff(int argc, char **argv);
int rf_cmd_grade(int argc, char **argv);
int rf_cmd_bench(int argc, char **argv);
int rf_cmd_export(int argc, char **argv);

#endif
