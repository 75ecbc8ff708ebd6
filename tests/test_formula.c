#include "rf_test.h"
const RfTest rf_tests_formula[] = {RF_TEST_END};
