/* The CIE tables compiled into refray (generated into cie_tables.c by
 * tools/oracle/gen_color_data.py; the CSV copies are in src/color/data/). Private to src/color. */
#ifndef REFRAY_CIE_TABLES_H
#define REFRAY_CIE_TABLES_H

typedef struct {
    int first_nm, step_nm, count;
    const double (*v)[3];
    const char *publication, *distribution;
} RfCieTable;

extern const RfCieTable rf_cie1931_xyz; /* x̄ ȳ z̄, 360–830 nm, 1 nm */
extern const RfCieTable rf_cie2006_lms; /* l̄ m̄ s̄, 390–830 nm, 1 nm */
extern const RfCieTable rf_cie1931_rgb; /* r̄ ḡ b̄, 380–780 nm, 5 nm */

#endif
