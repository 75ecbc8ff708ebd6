#include "rf_test.h"

const RfTest rf_tests_color[] = {RF_TEST_END};
