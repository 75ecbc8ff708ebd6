#include "rf_test.h"
const RfTest rf_tests_vecmat[] = {RF_TEST_END};
