#include "rf_test.h"
const RfTest rf_tests_transform[] = {RF_TEST_END};
