/* `refray formula` entries of §1 (filled in by their issue). */
#include "refray/formula.h"

const RfFormula rf_formulas_color[] = {
    {NULL, NULL, NULL, NULL, NULL, NULL, NULL},
};
