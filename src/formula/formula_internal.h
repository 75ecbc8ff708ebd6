/* Formula functions shared between the tables of several script sections. */
#ifndef REFRAY_FORMULA_INTERNAL_H
#define REFRAY_FORMULA_INTERNAL_H

#include "refray/formula.h"

/* eye, target, up -> u, v, w (§3.4), and with_view: the world-to-camera matrix (§4.7.2). */
int rf_formula_camera(RfFormulaCall *c, int with_view);

#endif
