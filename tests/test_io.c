#include "rf_test.h"

const RfTest rf_tests_io[] = {RF_TEST_END};
