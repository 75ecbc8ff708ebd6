#include "rf_test.h"
const RfTest rf_tests_geometry[] = {RF_TEST_END};
