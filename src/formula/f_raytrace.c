/* `refray formula` entries of §3 (filled in by their issue). */
#include "refray/formula.h"

const RfFormula rf_formulas_raytrace[] = {
    {NULL, NULL, NULL, NULL, NULL, NULL, NULL},
};
