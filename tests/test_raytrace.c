#include "rf_test.h"

const RfTest rf_tests_raytrace[] = {RF_TEST_END};
